#pragma once
// One number for a run's whole particle state: FNV-1a 64 over every particle
// field, force and torque and every contact of the history, particle by
// particle in ascending id. It does not depend on how the particles were
// split across ranks, so two runs (other rank counts, another build, before
// and after a refactor) agree bit for bit exactly when their digests agree.
// Nor on where the history keeps a contact: a particle's contacts count by
// ascending partner id, and a slot with a partner but every kept field +0 is
// no contact (a new contact starts from zero springs, so the two continue
// alike). So a history stored another way (slots claimed in another order,
// springs kept per Verlet list entry) digests the same when it holds the
// same contacts.
#include <cstdint>

#include "core/particle_snapshot.hpp"

namespace gs {

// `s` with every field, and `history` in the order of s's rows (entry
// (row r, slot k) at r * slots + k; empty without history).
std::uint64_t state_digest(const ParticleSnapshot& s, const HostHistory& history);

}  // namespace gs
