#pragma once
// Particles on the host, as plain arrays: what moves between ranks (migration
// and ghosts) and what checkpoints hold. Values are copied bit for bit.
#include <cstdint>
#include <vector>

#include "core/particle_store.hpp"

namespace gs {

// Contact history of particles on the host, in fp64 (exact for fp32 springs):
// entry (particle p, slot s) at p * slots + s.
struct HostHistory {
  int slots = 0;
  std::vector<ParticleId> partner;
  std::vector<Vec3d> tangential;  // empty unless friction is on
  std::vector<Vec3d> rolling;     // empty unless rolling resistance is on
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

}  // namespace gs
