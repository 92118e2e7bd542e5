#pragma once
// Between a checkpoint file and the state a run continues from.
#include "core/particle_snapshot.hpp"
#include "io/checkpoint.hpp"

namespace gs {

// The checkpoint of a whole run: `all` and `history` hold every particle, in id order.
Checkpoint make_checkpoint(ParticleSnapshot all, HostHistory history, const std::vector<Wall>& walls,
                           std::uint64_t scene_hash, int rank_count,
                           const std::optional<InsertionState>& insertion = std::nullopt);
// The same around particles and history already in c (c.particles and
// c.history: output fills them in place, reusing their memory).
void complete_checkpoint(Checkpoint& c, const std::vector<Wall>& walls, std::uint64_t scene_hash, int rank_count,
                         const std::optional<InsertionState>& insertion = std::nullopt);
RestartState restart_state(const Checkpoint& c);

}  // namespace gs
