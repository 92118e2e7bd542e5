#include "scene/scene_time_step.hpp"

#include <algorithm>
#include <limits>

#include "scene/number_text.hpp"
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

std::string time_step_problem(SceneSpec& s) {
  const StableStep limit = stable_time_step(s);
  s.stable_time_step = limit.time_step;
  s.stable_step_binding = limit.binding;
  if (!(s.time_step > 0)) return "time step " + number_text(s.time_step) + " s must be positive";
  if (s.time_step <= limit.time_step) return "";
  return "time step " + number_text(s.time_step) + " s (" + number_text(s.time_step / s.contact_time) +
         " of the contact time) exceeds the stability limit " + number_text(limit.time_step) + " s (" +
         number_text(limit.time_step / s.contact_time) + " of the contact time), set by the " + limit.binding +
         " in a dense bed (docs/STABILITY.md)";
}

}  // namespace gs
