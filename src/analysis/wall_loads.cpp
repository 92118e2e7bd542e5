#include "analysis/wall_loads.hpp"

#include <algorithm>
#include <cstddef>

#include "analysis/block_sum.hpp"
#include "contact/contact_law.hpp"
#include "contact/contact_models.hpp"
#include "walls/wall_geometry.hpp"
#include "walls/wall_screen.hpp"

namespace gs {
namespace {

// The stored springs of particle `id`'s contact with wall w (zero when none).
ContactState<double> stored_state(const ParticleRecords& on_walls, ParticleId id, int w) {
  ContactState<double> state;
  const auto at = std::lower_bound(on_walls.id.begin(), on_walls.id.end(), id);
  if (at == on_walls.id.end() || *at != id) return state;
  const HostHistory& h = on_walls.history;
  const std::size_t k = std::size_t(h.slots), i = std::size_t(at - on_walls.id.begin());
  for (std::size_t s = 0; s < k; ++s) {
    if (h.partner[i * k + s] != kWallPartnerBase + ParticleId(w)) continue;
    for_each_history_field(h, state, [&](const char*, unsigned, const auto& rows, auto& value) {
      if (!rows.empty()) value = rows[i * k + s];
    });
  }
  return state;
}

// Particle i's load on each wall it touches, taken off out[w] (the wall
// feels the opposite of what the particle feels). Each wall behind the force
// kernel's cheap first test (walls/wall_screen.hpp), which passes every
// contact that wall_contact finds.
template <class Model, unsigned Effects>
void add_loads(const std::vector<PairParams<double, Model>>& table, std::size_t n, const std::vector<Wall>& walls,
               const std::vector<WallScreen>& screens, const ParticleSnapshot& s, const ParticleRecords& on_walls,
               std::size_t i, MeshLoad* out) {
  for (std::size_t w = 0; w < walls.size(); ++w) {
    WallContact wc;
    if (!wall_may_touch(screens[w], s.position[i], double(s.radius[i])) ||
        !wall_contact(walls[w], s.position[i], double(s.radius[i]), wc))
      continue;
    ContactKinematics<double> k;
    k.overlap = wc.overlap;
    k.normal = wc.normal;
    k.lever = double(s.radius[i]) - k.overlap;
    k.velocity = s.velocity[i] - wc.wall_velocity - cross(s.angular_velocity[i] * k.lever, k.normal);
    k.angular_velocity = s.angular_velocity[i] - walls[w].angular_velocity;
    k.effective_mass = s.mass[i];
    k.effective_radius = s.radius[i];
    ContactState<double> state = stored_state(on_walls, s.id[i], int(w));
    const ContactLoad<double> load = contact_load<double, Model, Effects>(
        table[std::size_t(s.material[i]) * n + std::size_t(walls[w].material)], k, state, 0.0);
    const Vec3d centre = walls[w].axis_point + walls[w].shift;
    out[w].force -= load.force;
    out[w].torque -= cross(wc.point - centre, load.force);
    if constexpr ((Effects & (kFriction | kRollingResistance)) != 0) {
      // The particle's couple about its centre, moved to the contact point.
      out[w].torque -= load.torque - cross(wc.point - s.position[i], load.force);
    }
  }
}

// Summed in fixed blocks (analysis/block_sum.hpp): one thread over every
// particle took 0.09 us per particle on the host (a time-series row of 64e6
// spheres: about 6 s).
template <class Model, unsigned Effects>
std::vector<MeshLoad> loads(const SceneSpec& scene, const std::vector<Wall>& walls, const ParticleSnapshot& s,
                            const ParticleRecords& on_walls) {
  const std::vector<PairParams<double, Model>> table = make_pair_table<double, Model>(scene.materials, scene.pairs);
  const std::size_t n = scene.materials.size();
  std::vector<WallScreen> screens;
  for (const Wall& w : walls) screens.push_back(wall_screen(w));
  return sum_in_blocks(
      s.size(), std::vector<MeshLoad>(walls.size()),
      [&](std::vector<MeshLoad>& out, std::size_t i) {
        add_loads<Model, Effects>(table, n, walls, screens, s, on_walls, i, out.data());
      },
      [](std::vector<MeshLoad>& total, const std::vector<MeshLoad>& block) {
        for (std::size_t w = 0; w < total.size(); ++w) {
          total[w].force += block[w].force;
          total[w].torque += block[w].torque;
        }
      });
}

template <class Model>
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
  return with_contact_model(scene.model, [&](auto model) {
    return for_effects<decltype(model)>(scene, walls, s, on_walls);
  });
}

}  // namespace gs
