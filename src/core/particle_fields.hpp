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
//     sub-micrometre resolution and long runs do not drift (angular velocity
//     kept only by runs whose spheres can spin: something makes torques, or
//     a particle starts spinning);
//   radius, mass, moment of inertia: fp32 (material constants of a particle);
//   orientation quaternion: fp32, renormalised every step (visualisation
//     only: kept and integrated only by runs whose snapshots hold it);
//   force, torque and the history: the force precision, fp32 or fp64 (the
//     host holds the history in fp64, exact for fp32).
#include <cstdint>

#include "core/periodic_box.hpp"
#include "core/types.hpp"
#include "core/vec3.hpp"

namespace gs {

struct Quaternion {
  float w, x, y, z;
};
constexpr Quaternion kNoRotation{1, 0, 0, 0};

// Fields that only some runs keep (a bit each); a run that does not keep one
// leaves it empty everywhere (store, records, snapshots, messages,
// checkpoints), so it costs nothing in memory or traffic.
enum ParticleField : unsigned {
  kEveryRun = 0u,     // not optional: every run keeps the field
  kImageCounts = 1u,  // periodic runs: crossings of each periodic face (core/periodic_box.hpp)
  kFrozenFlags = 2u,  // runs with frozen particle sets: 1 for a particle that never moves
  kOrientations = 4u,  // runs whose snapshots hold orientations: nothing else reads them
  // Runs whose spheres can spin: an effect makes torques (friction, rolling
  // resistance), or a particle starts with an angular velocity. Without, every
  // sphere's spin stays zero: its output reads zeros (ParticleMover::owned_to_host).
  kAngularVelocities = 8u,
};

// The value an optional field starts from where nothing set it (a new
// particle; a restart from a checkpoint of a run that did not keep the
// field): no face crossed, not frozen, not rotated.
template <class T>
constexpr T start_value() {
  return T{};
}
template <>
constexpr Quaternion start_value<Quaternion>() {
  return kNoRotation;
}

// X(name, type, kept): the state of one particle, in the order messages,
// records and checkpoints hold it; kept is kEveryRun or the ParticleField bit
// of a field only some runs keep. Every kept field travels with a migrating
// particle, in ghost messages and in checkpoints.
#define GS_PARTICLE_FIELDS(X)              \
  X(id, ParticleId, kEveryRun)             \
  X(material, std::uint8_t, kEveryRun)     \
  X(marker, std::uint8_t, kEveryRun)       \
  X(radius, float, kEveryRun)              \
  X(mass, float, kEveryRun)                \
  X(inertia, float, kEveryRun)             \
  X(position, Vec3d, kEveryRun)            \
  X(velocity, Vec3d, kEveryRun)            \
  X(angular_velocity, Vec3d, kAngularVelocities) \
  X(orientation, Quaternion, kOrientations) \
  X(image, ImageCount, kImageCounts)      \
  X(frozen, std::uint8_t, kFrozenFlags)

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
#define GS_VISIT_FIELD(name, type, kept) f(#name, a.name);
  GS_PARTICLE_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

// f(name, field of a, field of b) for each particle field of a and b.
template <class A, class B, class F>
void for_each_particle_field(A& a, B& b, F&& f) {
#define GS_VISIT_FIELD(name, type, kept) f(#name, a.name, b.name);
  GS_PARTICLE_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

// The same over the fields a run keeps: every kEveryRun field and the
// optional ones whose bit is in `kept` (a set of ParticleField bits).
template <class A, class F>
void for_each_kept_particle_field(A& a, unsigned kept, F&& f) {
#define GS_VISIT_FIELD(name, type, bit) \
  if ((bit) == kEveryRun || (kept & (bit)) != 0) f(#name, a.name);
  GS_PARTICLE_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

template <class A, class B, class F>
void for_each_kept_particle_field(A& a, B& b, unsigned kept, F&& f) {
#define GS_VISIT_FIELD(name, type, bit) \
  if ((bit) == kEveryRun || (kept & (bit)) != 0) f(#name, a.name, b.name);
  GS_PARTICLE_FIELDS(GS_VISIT_FIELD)
#undef GS_VISIT_FIELD
}

// f(name, bit, field) for each particle field of `a`, with its ParticleField bit.
template <class A, class F>
void for_each_particle_field_bit(A& a, F&& f) {
#define GS_VISIT_FIELD(name, type, bit) f(#name, unsigned(bit), a.name);
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
