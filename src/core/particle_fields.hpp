#pragma once
// Every per-particle field and every per-contact history field, declared
// once. What holds or moves particles is derived from these two lists: the
// store on the backend (engine/particle_store.hpp), the host records and
// snapshots (core/particle_records.hpp, core/particle_snapshot.hpp), rank
// messages (engine/particle_message.hpp, engine/step_kernels_transfer.hpp,
// comm/records_codec.cpp), checkpoints (io/checkpoint*.cpp) and the state
// digest. A new field is one line here plus its physics (docs/DESIGN.md).
//
// Precision per field:
//   position, velocity, angular velocity: fp64, so a 1e5 m domain keeps
//     sub-micrometre resolution and long runs do not drift;
//   radius, mass, moment of inertia: fp32 (material constants of a particle);
//   orientation quaternion: fp32, renormalised every step (visualisation only);
//   force, torque and the history: the force precision, fp32 or fp64 (the
//     host holds the history in fp64, exact for fp32).
#include <cstdint>

#include "core/types.hpp"
#include "core/vec3.hpp"

namespace gs {

struct Quaternion {
  float w, x, y, z;
};

// X(name, type): the state of one particle, in the order messages, records
// and checkpoints hold it. Every field travels with a migrating particle, in
// ghost messages and in checkpoints.
#define GS_PARTICLE_FIELDS(X)   \
  X(id, ParticleId)             \
  X(material, std::uint8_t)     \
  X(marker, std::uint8_t)       \
  X(radius, float)              \
  X(mass, float)                \
  X(inertia, float)             \
  X(position, Vec3d)            \
  X(velocity, Vec3d)            \
  X(angular_velocity, Vec3d)    \
  X(orientation, Quaternion)

// The value of a history field in precision Real.
template <class Real>
using HistoryVector = Vec3<Real>;
template <class Real>
using HistoryScalar = Real;

// Which history fields a run keeps (a bit each): the contact model and the
// effects decide (contact/contact_models.hpp, history_fields_kept).
enum HistoryField : unsigned {
  kTangentialSprings = 1u,  // elastic tangential force f_e [N] (friction)
  kRollingSprings = 2u,     // rolling spring displacement xi_r [m] (rolling resistance)
  kPeakOverlap = 4u,        // largest overlap of the contact so far [m] (hysteretic normal laws)
};
// The fields of checkpoint format 2, which predates the list: they always
// count in the checksum, kept or not (io/checkpoint.cpp).
constexpr unsigned kFormat2HistoryFields = kTangentialSprings | kRollingSprings;

// X(name, value, bit): the history of one contact beside its partner id, in
// the order messages and checkpoints hold it; value<Real> is its type.
#define GS_HISTORY_FIELDS(X)                          \
  X(tangential, HistoryVector, kTangentialSprings)    \
  X(rolling, HistoryVector, kRollingSprings)          \
  X(peak_overlap, HistoryScalar, kPeakOverlap)

// f(name, field) for each particle field of `a` (a store, records, a snapshot).
template <class A, class F>
void for_each_particle_field(A& a, F&& f) {
#define GS_VISIT_FIELD(name, type) f(#name, a.name);
  GS_PARTICLE_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

// f(name, field of a, field of b) for each particle field of a and b.
template <class A, class B, class F>
void for_each_particle_field(A& a, B& b, F&& f) {
#define GS_VISIT_FIELD(name, type) f(#name, a.name, b.name);
  GS_PARTICLE_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

// f(name, bit, field) for each history field of `h` (kept or not).
template <class H, class F>
void for_each_history_field(H& h, F&& f) {
#define GS_VISIT_FIELD(name, value, bit) f(#name, bit, h.name);
  GS_HISTORY_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

template <class A, class B, class F>
void for_each_history_field(A& a, B& b, F&& f) {
#define GS_VISIT_FIELD(name, value, bit) f(#name, bit, a.name, b.name);
  GS_HISTORY_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

}  // namespace gs
