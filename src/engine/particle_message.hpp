#pragma once
// One message of particles between ranks, packed by backend kernels into one
// buffer in backend memory, so that moving it costs one copy (or one NCCL
// send) instead of one per field. The header travels on the host; the payload
// holds each field for all particles in turn, every field 8-byte aligned:
// id, material, marker, radius, mass, inertia, position, velocity, angular
// velocity, orientation, then the history (slot-major: entry s * count + i):
// partners, tangential springs, rolling springs, in the force precision.
#include <cstddef>
#include <cstdint>

#include "core/particle_store.hpp"

namespace gs {

struct MessageHeader {
  std::uint64_t count = 0;     // particles
  std::int32_t slots = 0;      // history slots per particle; 0: no history carried
  std::int32_t spring_bytes = 0;  // bytes of one spring (sizeof(Vec3<Real>)); 0: no springs
  std::uint32_t springs = 0;   // bit 0: tangential, bit 1: rolling
  std::uint32_t check = 0;     // kMessageCheck: a header that is not one is refused
};
constexpr std::uint32_t kMessageCheck = 0x67734d31u;  // "gsM1"
constexpr std::uint32_t kTangentialSprings = 1u, kRollingSprings = 2u;

struct MessageLayout {
  std::size_t id, material, marker, radius, mass, inertia, position, velocity, angular_velocity, orientation;
  std::size_t partner, tangential, rolling;  // meaningful only when carried
  std::size_t bytes;                         // the whole payload

  explicit MessageLayout(const MessageHeader& h) {
    const std::size_t m = h.count, slots = std::size_t(h.slots), spring = std::size_t(h.spring_bytes);
    std::size_t at = 0;
    auto field = [&](std::size_t each) {
      const std::size_t here = at;
      at += (each * m + 7) / 8 * 8;
      return here;
    };
    id = field(sizeof(ParticleId));
    material = field(1);
    marker = field(1);
    radius = field(sizeof(float));
    mass = field(sizeof(float));
    inertia = field(sizeof(float));
    position = field(sizeof(Vec3d));
    velocity = field(sizeof(Vec3d));
    angular_velocity = field(sizeof(Vec3d));
    orientation = field(sizeof(Quaternion));
    partner = field(slots * sizeof(ParticleId));
    tangential = field((h.springs & kTangentialSprings) ? slots * spring : 0);
    rolling = field((h.springs & kRollingSprings) ? slots * spring : 0);
    bytes = at;
  }
};

}  // namespace gs
