// `inlets:` -> SceneSpec::inlets (docs/SCENES.md): where, how fast and what
// particles are inserted during the run, and the checks that refuse an inlet
// that cannot work (outside the domain, sizes that do not fit, a rate no
// batch can place).
#include <algorithm>
#include <climits>
#include <cmath>

#include "scene/scene_sections.hpp"

namespace gs::scene_yaml {

namespace {

// Random sequential addition into an empty region jams near a solid fraction
// of 0.38 (monodisperse spheres, Feder 1980); well below it a batch is placed
// in a few tries per particle. A batch due to fill more of its region than
// this is refused: the rate cannot be placed.
constexpr double kMaxBatchFraction = 0.2;

const std::vector<std::string> kInletKeys = {
    "name",  "material", "region", "radius",   "diameter_distribution", "fractions_by", "rate",
    "total", "start",    "stop",   "interval", "velocity",              "velocity_spread", "angular_velocity",
    "marker", "seed",    "attempts"};

InletSpec::Amount amount_of(const Val& v, double& value) {
  const Map m(v, {"count", "mass"});
  const std::string kind = m.one_of({"count", "mass"});
  value = positive(m.get(kind));
  return kind == "count" ? InletSpec::Amount::count : InletSpec::Amount::mass;
}

// Refuses a region that reaches outside the domain: particles placed there
// would be lost at once.
void check_in_domain(const SceneSpec& s, const FillRegion& region, const Val& where) {
  Vec3d lo, hi;
  region_bounds(region, lo, hi);
  const Vec3d &dlo = s.domain_min, &dhi = s.domain_max;
  if (lo.x < dlo.x || lo.y < dlo.y || lo.z < dlo.z || hi.x > dhi.x || hi.y > dhi.y || hi.z > dhi.z)
    fail(where, "the inlet region " + str(lo) + " .. " + str(hi) + " is not inside the domain " + str(dlo) + " .. " +
                    str(dhi));
}

InletSpec parse_inlet(const SceneSpec& s, const Val& item, std::size_t index) {
  const Map m(item, kInletKeys);
  InletSpec in;
  in.name = m.has("name") ? text(m.get("name")) : "inlet " + std::to_string(index);
  in.key = located(item, "");
  in.key.resize(in.key.size() - 2);  // "<file>:<line>: inlets[i]" without the trailing ": "
  in.tmpl = parse_template(s, m);
  in.velocity_spread = number_or(m, "velocity_spread", 0.0, nonnegative);
  in.region = parse_region(m.get("region"));
  check_in_domain(s, in.region, m.get("region"));
  in.size = parse_sizes(m);
  const Val size_key = m.has("radius") ? m.get("radius") : m.get("diameter_distribution");
  if (!fits(in.region, largest_radius(in.size)))
    fail(size_key, "a particle of radius " + str(largest_radius(in.size)) + " does not fit in the inlet region");
  if (!m.has("rate") && !m.has("total")) fail(item, "an inlet needs a rate, a total, or both");
  if (m.has("rate")) in.rate_of = amount_of(m.get("rate"), in.rate);
  if (m.has("total")) in.total_of = amount_of(m.get("total"), in.total);
  if (m.has("total") && in.total_of == InletSpec::Amount::count && in.total > double(kMaxParticleId))
    fail(m.get("total"), "more particles than the 32-bit ids hold");
  in.start = number_or(m, "start", 0.0, nonnegative);
  if (!(in.start < s.duration))
    fail(m.get("start"), "must lie before the end of the run (duration " + str(s.duration) + " s), got " + str(in.start));
  if (m.has("stop")) {
    in.stop = positive(m.get("stop"));
    if (!(in.stop > in.start)) fail(m.get("stop"), "must lie after start " + str(in.start) + " s, got " + str(in.stop));
  }
  if (m.has("seed")) in.seed = std::uint64_t(integer(m.get("seed"), 0, LLONG_MAX));
  if (m.has("attempts")) in.attempts = int(integer(m.get("attempts"), 1, 10000));
  return in;
}

}  // namespace

void parse_inlets(const Map& top, SceneSpec& s) {
  if (!top.has("inlets")) return;
  for_each_item(top.get("inlets"), [&](const Val& item, std::size_t i) {
    s.inlets.push_back(parse_inlet(s, item, i));
    for (std::size_t j = 0; j + 1 < s.inlets.size(); ++j)
      if (s.inlets[j].name == s.inlets.back().name)
        fail(item, "the inlet name " + quoted(s.inlets.back().name) + " is used twice");
  });
}

// Needs the time step: `interval` becomes a whole number of steps, and the
// volume due per batch is checked against the region.
void check_inlet_rates(const Map& top, SceneSpec& s) {
  if (!top.has("inlets")) return;
  const Val list = top.get("inlets");
  for_each_item(list, [&](const Val& item, std::size_t i) {
    const Map m(item, kInletKeys);
    InletSpec& in = s.inlets[i];
    if (m.has("interval")) {
      const Val v = m.get("interval");
      const double interval = positive(v);
      in.interval_steps = std::max(1LL, std::llround(interval / s.time_step));
    }
    if (in.rate == 0) return;
    const double seconds = double(in.interval_steps) * s.time_step;
    const double density = s.materials[std::size_t(in.tmpl.material)].density;
    const double per_particle = mean_particle_volume(in.size);
    const double volume = in.rate_of == InletSpec::Amount::count ? in.rate * seconds * per_particle
                                                                  : in.rate * seconds / density;
    const double fraction = volume / region_volume(in.region);
    if (fraction > kMaxBatchFraction)
      fail(m.get("rate"), "cannot be placed: a batch (every " + str(seconds) + " s) brings " + str(volume) +
                              " m^3 of particles, " + str(100 * fraction) + " % of the inlet region's volume; " +
                              "random placement is refused above " + str(100 * kMaxBatchFraction) +
                              " %: enlarge the region, lower the rate or shorten the interval");
  });
}

}  // namespace gs::scene_yaml
