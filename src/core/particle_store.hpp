#pragma once
// All particle state of one rank as a structure of arrays in backend memory.
// Precision per field (docs/PRECISION.md says why):
//   position, velocity, angular velocity: fp64, so a 1e5 m domain keeps
//     sub-micrometre resolution and long runs do not drift;
//   radius, mass, moment of inertia: fp32 (material constants of a particle);
//   orientation quaternion: fp32, renormalised every step (visualisation only);
//   force, torque, contact springs: the force precision, fp32 or fp64.
// Owned particles occupy [0, n_owned); ghost copies of neighbours' particles
// follow in [n_owned, n_owned + n_ghost).
#include <cstdint>

#include "backend/device_array.hpp"
#include "core/history_layout.hpp"
#include "core/types.hpp"
#include "core/vec3.hpp"

namespace gs {

struct Quaternion {
  float w, x, y, z;
};

template <class Real>
struct ForceArrays {
  DeviceArray<Vec3<Real>> force;   // contact force [N]
  DeviceArray<Vec3<Real>> torque;  // contact torque [N m]
};

// Spring history of up to `capacity` particles, laid out as `strides` says
// (core/history_layout.hpp; the execution policy picks the order).
template <class Real>
struct ContactHistory {
  int slots = 0;
  std::size_t capacity = 0;
  HistoryStrides strides;
  DeviceArray<ParticleId> partner;        // kNoPartner marks a free slot
  DeviceArray<Vec3<Real>> tangential;     // empty unless friction is on
  DeviceArray<Vec3<Real>> rolling;        // empty unless rolling resistance is on
};

struct ParticleStore {
  Backend backend = Backend::cpu;
  Index n_owned = 0;
  Index n_ghost = 0;

  DeviceArray<ParticleId> id;
  DeviceArray<std::uint8_t> material;
  DeviceArray<std::uint8_t> marker;
  DeviceArray<float> radius, mass, inertia;
  DeviceArray<Vec3d> position, velocity, angular_velocity;
  DeviceArray<Quaternion> orientation;

  Index size() const { return n_owned + n_ghost; }

  // Sets the length of every array (contents up to min(old, n) are kept).
  void resize_arrays(std::size_t n) {
    id.resize(n);
    material.resize(n);
    marker.resize(n);
    radius.resize(n);
    mass.resize(n);
    inertia.resize(n);
    position.resize(n);
    velocity.resize(n);
    angular_velocity.resize(n);
    orientation.resize(n);
  }
  void drop_ghosts() {
    n_ghost = 0;
    resize_arrays(std::size_t(n_owned));
  }
};

}  // namespace gs
