#include "analysis/wall_loads.hpp"

#include <algorithm>

#include "contact/contact_law.hpp"
#include "engine/step_kernels.hpp"
#include "walls/wall_geometry.hpp"

namespace gs {
namespace {

// The stored springs of particle `id`'s contact with wall w (zero when none).
ContactSprings<double> stored_springs(const ParticleRecords& on_walls, ParticleId id, int w) {
  ContactSprings<double> springs;
  const auto at = std::lower_bound(on_walls.id.begin(), on_walls.id.end(), id);
  if (at == on_walls.id.end() || *at != id) return springs;
  const HostHistory& h = on_walls.history;
  const std::size_t k = std::size_t(h.slots), i = std::size_t(at - on_walls.id.begin());
  for (std::size_t s = 0; s < k; ++s) {
    if (h.partner[i * k + s] != kWallPartnerBase + ParticleId(w)) continue;
    if (!h.tangential.empty()) springs.tangential = h.tangential[i * k + s];
    if (!h.rolling.empty()) springs.rolling = h.rolling[i * k + s];
  }
  return springs;
}

template <ContactModel Model, unsigned Effects>
std::vector<MeshLoad> loads(const SceneSpec& scene, const std::vector<Wall>& walls, const ParticleSnapshot& s,
                            const ParticleRecords& on_walls) {
  const PairTableHost table = make_pair_table(scene);
  std::vector<MeshLoad> out(walls.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t w = 0; w < walls.size(); ++w) {
      WallContact wc;
      if (!wall_contact(walls[w], s.position[i], double(s.radius[i]), wc)) continue;
      ContactKinematics<double> k;
      k.overlap = wc.overlap;
      k.normal = wc.normal;
      k.lever = double(s.radius[i]) - k.overlap;
      k.velocity = s.velocity[i] - wc.wall_velocity - cross(s.angular_velocity[i] * k.lever, k.normal);
      k.angular_velocity = s.angular_velocity[i] - walls[w].angular_velocity;
      k.effective_mass = s.mass[i];
      k.effective_radius = s.radius[i];
      ContactSprings<double> springs = stored_springs(on_walls, s.id[i], int(w));
      const ContactLoad<double> load = contact_load<double, Model, Effects>(
          pair_params<double>(table, table.at(s.material[i], walls[w].material)), k, springs, 0.0);
      // The wall feels the opposite of what the particle feels.
      const Vec3d centre = walls[w].axis_point + walls[w].shift;
      out[w].force -= load.force;
      out[w].torque -= cross(wc.point - centre, load.force);
      if constexpr ((Effects & (kFriction | kRollingResistance)) != 0) {
        // The particle's couple about its centre, moved to the contact point.
        out[w].torque -= load.torque - cross(wc.point - s.position[i], load.force);
      }
    }
  return out;
}

template <ContactModel Model>
std::vector<MeshLoad> for_effects(const SceneSpec& scene, const std::vector<Wall>& walls, const ParticleSnapshot& s,
                                  const ParticleRecords& on_walls) {
  switch (scene.effects & kAllEffects) {
    case 0: return loads<Model, 0>(scene, walls, s, on_walls);
    case 1: return loads<Model, 1>(scene, walls, s, on_walls);
    case 2: return loads<Model, 2>(scene, walls, s, on_walls);
    case 3: return loads<Model, 3>(scene, walls, s, on_walls);
    case 4: return loads<Model, 4>(scene, walls, s, on_walls);
    case 5: return loads<Model, 5>(scene, walls, s, on_walls);
    case 6: return loads<Model, 6>(scene, walls, s, on_walls);
    default: return loads<Model, 7>(scene, walls, s, on_walls);
  }
}

}  // namespace

std::vector<MeshLoad> wall_loads(const SceneSpec& scene, const std::vector<Wall>& walls, const ParticleSnapshot& s,
                                 const ParticleRecords& on_walls) {
  if (scene.model == ContactModel::linear) return for_effects<ContactModel::linear>(scene, walls, s, on_walls);
  return for_effects<ContactModel::hertz_mindlin>(scene, walls, s, on_walls);
}

}  // namespace gs
