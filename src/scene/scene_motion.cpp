// A wall entry's `motion` and `active` keys (docs/SCENES.md, walls): the
// constant motion in the prescribed Wall, tables, oscillation and the active
// window in its Timeline.
#include <cmath>
#include <stdexcept>

#include "scene/scene_motion.hpp"

namespace gs::scene_yaml {
namespace {

constexpr double kRadPerSecondPerRpm = 2.0 * M_PI / 60.0;

// `{times: [...], values: [...]}`: times from 0, strictly increasing; each
// value read by `read` and scaled into the table's unit by `to_rate`.
template <class Read>
RateTable parse_table(const Val& v, Read read) {
  const Map m(v, {"times", "values"});
  std::vector<double> time;
  std::vector<Vec3d> value;
  for_each_item(m.get("times"), [&](const Val& t, std::size_t k) {
    time.push_back(nonnegative(t));
    if (k == 0 && time[0] != 0) fail(t, "the first time must be 0 (the start of the motion), got " + str(time[0]));
    if (k > 0 && !(time[k] > time[k - 1]))
      fail(t, "times must increase strictly: " + str(time[k]) + " s is not after " + str(time[k - 1]) + " s");
  });
  for_each_item(m.get("values"), [&](const Val& x, std::size_t) { value.push_back(read(x)); });
  if (value.size() != time.size())
    fail(m.get("values"), std::to_string(value.size()) + " values for " + std::to_string(time.size()) + " times");
  if (time.empty()) fail(m.get("times"), "a table needs at least one time");
  return make_rate_table(std::move(time), std::move(value));
}

// `velocity`: a vector (constant) or a table of vectors.
void parse_velocity(const Val& v, Wall& w, Timeline& s) {
  if (v.node.IsMap()) s.velocity = parse_table(v, [](const Val& x) { return vec3(x); });
  else w.velocity = vec3(v);
}

// `rotation`: axis_point, axis and one of rpm / angular_speed [rad/s], each a
// number (constant) or a table of numbers.
void parse_rotation(const Val& v, Wall& w, Timeline& s) {
  const Map r(v, {"axis_point", "axis", "rpm", "angular_speed"});
  w.axis_point = vec3(r.get("axis_point"));
  const Vec3d axis = unit_vector(r.get("axis"));
  const std::string key = r.one_of({"rpm", "angular_speed"});
  const double scale = key == "rpm" ? kRadPerSecondPerRpm : 1.0;
  const Val rate = r.get(key);
  if (rate.node.IsMap())
    s.angular_velocity = parse_table(rate, [&](const Val& x) { return axis * (number(x) * scale); });
  else
    w.angular_velocity = axis * (number(rate) * scale);
}

// `oscillation: {direction, amplitude, frequency, phase}`.
Oscillation parse_oscillation(const Val& v) {
  const Map m(v, {"direction", "amplitude", "frequency", "phase"});
  Oscillation o;
  o.amplitude = unit_vector(m.get("direction")) * positive(m.get("amplitude"));
  o.frequency = positive(m.get("frequency"));
  o.phase = number_or(m, "phase", 0.0, number);
  return o;
}

}  // namespace

void parse_motion(const Val& v, Wall& w, Timeline& s) {
  const Map m(v, {"velocity", "rotation", "oscillation", "start"});
  if (m.has("velocity")) parse_velocity(m.get("velocity"), w, s);
  w.motion_start = number_or(m, "start", 0.0, nonnegative);
  if (m.has("rotation")) parse_rotation(m.get("rotation"), w, s);
  if (m.has("oscillation")) s.oscillation = parse_oscillation(m.get("oscillation"));
}

ActiveWindow parse_active(const Val& v) {
  const Map m(v, {"from", "until"});
  ActiveWindow a;
  a.from = number_or(m, "from", 0.0, nonnegative);
  if (m.has("until")) {
    a.until = nonnegative(m.get("until"));
    if (!(a.until > a.from))
      fail(m.get("until"), "must be after `from` (" + str(a.from) + " s), got " + str(a.until) + " s");
  }
  return a;
}

}  // namespace gs::scene_yaml
