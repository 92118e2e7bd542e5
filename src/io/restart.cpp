#include "io/restart.hpp"

#include <utility>

namespace gs {

Checkpoint make_checkpoint(ParticleSnapshot all, HostHistory history, const std::vector<Wall>& walls,
                           std::uint64_t scene_hash, int rank_count,
                           const std::optional<InsertionState>& insertion) {
  Checkpoint c;
  c.step = all.step;
  c.time = all.time;
  c.particles = std::move(all);  // moved: a checkpoint's particles are its largest part
  c.history = std::move(history);
  c.walls = walls;
  c.scene_hash = scene_hash;
  c.rank_count = rank_count;
  c.decomposition_axis = -1;  // the partition is recomputed on restart, for any rank count
  c.insertion = insertion;
  return c;
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
