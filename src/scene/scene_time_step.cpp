#include "scene/scene_time_step.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

#include "scene/particle_sources.hpp"

namespace gs {

ContactScene contact_scene(const SceneSpec& s) {
  ContactScene c{s.model, s.effects, s.materials, s.pairs, {}};
  c.smallest_radius.assign(s.materials.size(), std::numeric_limits<double>::infinity());
  for_each_radius(s, [&c](int material, double radius) {
    double& r = c.smallest_radius[std::size_t(material)];
    r = std::min(r, radius);
  });
  return c;
}

double critical_contact_time(const SceneSpec& scene) { return critical_contact_time(contact_scene(scene)); }

StableStep stable_time_step(const SceneSpec& scene) { return stable_time_step(contact_scene(scene)); }

namespace {
// Six digits, as the loader's messages print numbers.
std::string str(double x) {
  std::ostringstream text;
  text.precision(6);
  text << x;
  return text.str();
}
}  // namespace

std::string time_step_problem(SceneSpec& s) {
  const StableStep limit = stable_time_step(s);
  s.stable_time_step = limit.time_step;
  s.stable_step_binding = limit.binding;
  if (!(s.time_step > 0)) return "time step " + str(s.time_step) + " s must be positive";
  if (s.time_step <= limit.time_step) return "";
  return "time step " + str(s.time_step) + " s (" + str(s.time_step / s.contact_time) +
         " of the contact time) exceeds the stability limit " + str(limit.time_step) + " s (" +
         str(limit.time_step / s.contact_time) + " of the contact time), set by the " + limit.binding +
         " in a dense bed (docs/STABILITY.md)";
}

}  // namespace gs
