#pragma once
// One number for a run's whole particle state: FNV-1a 64 over every particle
// field, force and torque and every contact of the history, particle by
// particle in ascending id. It does not depend on how the particles were
// split across ranks, so two runs (other rank counts, another build, before
// and after a refactor) agree bit for bit exactly when their digests agree.
#include <cstdint>

#include "core/particle_snapshot.hpp"

namespace gs {

// `s` with every field, and `history` in the order of s's rows (entry
// (row r, slot k) at r * slots + k; empty without history). Within a particle
// the contacts count in slot order, which the engine keeps rank-independent.
std::uint64_t state_digest(const ParticleSnapshot& s, const HostHistory& history);

}  // namespace gs
