#pragma once
// Particles on the host, as plain arrays: what moves between ranks (migration
// and ghosts) and what checkpoints hold. Values are copied bit for bit.
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/particle_fields.hpp"

namespace gs {

// Contact history of particles on the host, in fp64 (exact for fp32
// history): entry (particle p, slot s) at p * slots + s. A field the run does
// not keep is empty.
struct HostHistory {
  int slots = 0;
  std::vector<ParticleId> partner;
#define GS_DECLARE_FIELD(name, value, bit) std::vector<value<double>> name;
  GS_HISTORY_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD
};

struct ParticleRecords {
#define GS_DECLARE_FIELD(name, type, kept) std::vector<type> name;
  GS_PARTICLE_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD
  HostHistory history;  // empty (slots = 0) when not carried

  std::size_t size() const { return id.size(); }
};

// History row r of the result is row order[r] of h (core/particle_records.cpp).
HostHistory rows_permuted(const HostHistory& h, const std::vector<std::size_t>& order);

}  // namespace gs
