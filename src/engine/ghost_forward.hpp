#pragma once
// What a ghost receives between rebuilds of the halo (LAMMPS's forward_comm):
// the fields that change every step and that the force computation reads of a
// contact partner. ForceKernel (engine/force_kernel.hpp) reads of a partner
// its id, material, radius, mass, position, velocity and angular velocity
// (only in runs that keep it: core/particle_fields.hpp, kAngularVelocities);
// the first four never change, so they travel only when the halo is rebuilt
// (engine/particle_message.hpp). Marker, orientation and image counts change
// but no force reads them of a ghost. A kernel that starts reading another
// changing field of its partners adds it here.
//
// A forward message holds each field for all its particles in turn, in this
// order; sender and receiver know the count from the rebuild, so it carries
// no header.
#include <cstddef>

#include "engine/particle_store.hpp"

namespace gs {

// X(name, kept): kept as in GS_PARTICLE_FIELDS.
#define GS_FORWARD_FIELDS(X)  \
  X(position, kEveryRun)      \
  X(velocity, kEveryRun)      \
  X(angular_velocity, kAngularVelocities)

// Whether a run that keeps the optional fields `kept` forwards field `bit`.
inline bool forwards(unsigned bit, unsigned kept) { return bit == kEveryRun || (kept & bit) != 0; }

// Bytes of a forward message of m particles of a run that keeps the optional
// fields `kept` (every field 8-byte aligned, as each is a multiple of 8 bytes long).
inline std::size_t forward_bytes(std::size_t m, unsigned kept) {
  std::size_t bytes = 0;
#define GS_ADD_FIELD(name, bit) \
  if (forwards(bit, kept)) bytes += m * sizeof(decltype(ParticleStore::name)::value_type);
  GS_FORWARD_FIELDS(GS_ADD_FIELD)
#undef GS_ADD_FIELD
  return bytes;
}

}  // namespace gs
