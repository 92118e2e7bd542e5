#include "analysis/wall_loads.hpp"

#include <algorithm>
#include <cstddef>

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

// Particles per block of the sum. Each block sums its particles in id order,
// the blocks are added in order: a sum fixed by the snapshot alone (not by
// the threads that share the blocks, nor by the ranks: the snapshot is
// gathered in id order), over blocks that threads can share. One thread
// over every particle took 0.09 us per particle on the host (a time-series
// row of 64e6 spheres: about 6 s).
constexpr std::size_t kBlock = 4096;

template <class Model, unsigned Effects>
std::vector<MeshLoad> loads(const SceneSpec& scene, const std::vector<Wall>& walls, const ParticleSnapshot& s,
                            const ParticleRecords& on_walls) {
  const std::vector<PairParams<double, Model>> table = make_pair_table<double, Model>(scene.materials, scene.pairs);
  const std::size_t n = scene.materials.size(), n_walls = walls.size();
  const std::size_t blocks = (s.size() + kBlock - 1) / kBlock;
  std::vector<WallScreen> screens;
  for (const Wall& w : walls) screens.push_back(wall_screen(w));
  std::vector<MeshLoad> partial(blocks * n_walls);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::ptrdiff_t b = 0; b < std::ptrdiff_t(blocks); ++b) {
    MeshLoad* out = partial.data() + std::size_t(b) * n_walls;
    const std::size_t end = std::min(s.size(), (std::size_t(b) + 1) * kBlock);
    for (std::size_t i = std::size_t(b) * kBlock; i < end; ++i)
      add_loads<Model, Effects>(table, n, walls, screens, s, on_walls, i, out);
  }
  std::vector<MeshLoad> total(n_walls);
  for (std::size_t b = 0; b < blocks; ++b)
    for (std::size_t w = 0; w < n_walls; ++w) {
      total[w].force += partial[b * n_walls + w].force;
      total[w].torque += partial[b * n_walls + w].torque;
    }
  return total;
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
