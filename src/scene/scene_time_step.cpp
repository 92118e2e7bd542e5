#include "scene/scene_time_step.hpp"

#include <algorithm>
#include <limits>

namespace gs {

ContactScene contact_scene(const SceneSpec& s) {
  ContactScene c{s.model, s.effects, s.materials, s.pairs, {}};
  c.smallest_radius.assign(s.materials.size(), std::numeric_limits<double>::infinity());
  for (const ParticleInit& p : s.particles)
    c.smallest_radius[p.material] = std::min(c.smallest_radius[p.material], p.radius);
  return c;
}

double critical_contact_time(const SceneSpec& scene) { return critical_contact_time(contact_scene(scene)); }

StableStep stable_time_step(const SceneSpec& scene) { return stable_time_step(contact_scene(scene)); }

}  // namespace gs
