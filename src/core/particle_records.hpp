#pragma once
// Particles on the host, as plain arrays: what moves between ranks (migration
// and ghosts) and what checkpoints hold. Values are copied bit for bit.
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/particle_store.hpp"

namespace gs {

// Contact history of particles on the host, in fp64 (exact for fp32 springs):
// entry (particle p, slot s) at p * slots + s.
struct HostHistory {
  int slots = 0;
  std::vector<ParticleId> partner;
  std::vector<Vec3d> tangential;  // elastic tangential force [N]; empty unless friction is on
  std::vector<Vec3d> rolling;     // rolling displacement [m]; empty unless rolling resistance is on
};

struct ParticleRecords {
  std::vector<ParticleId> id;
  std::vector<std::uint8_t> material, marker;
  std::vector<float> radius, mass, inertia;
  std::vector<Vec3d> position, velocity, angular_velocity;
  std::vector<Quaternion> orientation;
  HostHistory history;  // empty (slots = 0) when not carried

  std::size_t size() const { return id.size(); }
};

// History row r of the result is row order[r] of h.
inline HostHistory rows_permuted(const HostHistory& h, const std::vector<std::size_t>& order) {
  const std::size_t k = std::size_t(h.slots);
  auto rows = [&](const auto& from) {
    std::decay_t<decltype(from)> to(from.empty() ? 0 : order.size() * k);
    for (std::size_t r = 0; r < order.size() && !from.empty(); ++r)
      for (std::size_t s = 0; s < k; ++s) to[r * k + s] = from[order[r] * k + s];
    return to;
  };
  HostHistory out;
  out.slots = h.slots;
  out.partner = rows(h.partner);
  out.tangential = rows(h.tangential);
  out.rolling = rows(h.rolling);
  return out;
}

}  // namespace gs
