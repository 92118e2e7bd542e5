#include "io/restart.hpp"

#include <utility>

namespace gs {

Checkpoint make_checkpoint(ParticleSnapshot all, HostHistory history, const std::vector<Wall>& walls,
                           std::uint64_t scene_hash, int rank_count,
                           const std::optional<InsertionState>& insertion) {
  Checkpoint c;
  c.particles = std::move(all);  // moved: a checkpoint's particles are its largest part
  c.history = std::move(history);
  complete_checkpoint(c, walls, scene_hash, rank_count, insertion);
  return c;
}

void complete_checkpoint(Checkpoint& c, const std::vector<Wall>& walls, std::uint64_t scene_hash, int rank_count,
                         const std::optional<InsertionState>& insertion) {
  c.step = c.particles.step;
  c.time = c.particles.time;
  c.walls = walls;
  c.scene_hash = scene_hash;
  c.rank_count = rank_count;
  c.decomposition_axis = -1;  // the partition is recomputed on restart, for any rank count
  c.decomposition_cuts.clear();
  c.random_state = 0;
  c.insertion = insertion;
}

RestartState restart_state(const Checkpoint& c) {
  RestartState r;
  r.step = c.step;
  r.time = c.time;
  const ParticleSnapshot& p = c.particles;
  for_each_particle_field(r.particles, p, [](const char*, auto& to, const auto& from) { to = from; });
  r.particles.history = c.history;
  r.force = p.force;
  r.torque = p.torque;
  r.insertion = c.insertion;
  return r;
}

}  // namespace gs
