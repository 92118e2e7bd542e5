#include "scene/scene_time_step.hpp"

#include <algorithm>
#include <limits>

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

}  // namespace gs
