#pragma once
#include <cstdint>

namespace gs {

// Global particle id, unique across ranks and stable for a particle's life.
// 32 bits keep the per-step sort key (cell, id) in one 64-bit word. Partner
// ids of the contact history: particles below kMeshPartnerBase, mesh features
// in [kMeshPartnerBase, kWallPartnerBase), analytic walls in the top 256 values.
using ParticleId = std::uint32_t;
// Local (per-rank) particle index.
using Index = std::int32_t;

constexpr ParticleId kNoPartner = 0xFFFFFFFFu;
constexpr ParticleId kWallPartnerBase = 0xFFFFFF00u;  // wall w is partner kWallPartnerBase + w
// Mesh feature (kind k: 0 face, 1 edge, 2 vertex; index n < kMaxMeshFeatures)
// is partner kMeshPartnerBase | k << 28 | n (mesh_partner_id, engine/force_kernel.hpp).
constexpr ParticleId kMeshPartnerBase = 0xC0000000u;
constexpr std::int32_t kMaxMeshFeatures = 1 << 28;  // triangles, edges and vertices of all meshes, each
constexpr ParticleId kMaxParticleId = kMeshPartnerBase - 1;
// Whether a history entry's partner is a particle: not empty (kNoPartner),
// not a wall or mesh feature.
constexpr bool names_particle(ParticleId partner) { return partner <= kMaxParticleId; }
constexpr int kMaxWalls = 255;
constexpr int kMaxContactSlots = 32;  // one bit per slot in a 32-bit mask

// Effects a scene can switch on; the step kernels are compiled once per set.
enum Effect : unsigned {
  kFriction = 1u,          // tangential spring with history and Coulomb cap
  kRollingResistance = 2u, // rolling spring with history and cap
  kCohesion = 4u,          // attractive normal force while in contact
};
constexpr unsigned kAllEffects = kFriction | kRollingResistance | kCohesion;

// The contact models (contact/contact_models.hpp lists their policy types).
enum class ContactModel : std::uint8_t { linear, hertz_mindlin, hysteretic_linear };
// Precision of a run: fp32 forces with fp64 state (the default), fp64
// forces, or fp32 throughout (positions and velocities rounded to fp32 after
// every update, as a code that stores them in fp32; docs/PHYSICS.md).
enum class Precision { fp32, fp64, fp32_full };

inline bool fp32_forces(Precision p) { return p != Precision::fp64; }
inline bool fp32_state(Precision p) { return p == Precision::fp32_full; }
inline const char* precision_name(Precision p) {
  return p == Precision::fp64 ? "fp64" : p == Precision::fp32 ? "fp32" : "fp32_full";
}

// Whether the effects make contact torques (and keep springs in the history).
constexpr bool makes_torques(unsigned effects) { return (effects & (kFriction | kRollingResistance)) != 0; }

}  // namespace gs
