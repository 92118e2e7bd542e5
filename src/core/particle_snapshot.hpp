#pragma once
// Particles on the host as output, analysis and restarts see them: what the
// engine hands to the layers above it, so that they need not know the engine.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/insertion_state.hpp"
#include "core/particle_records.hpp"

namespace gs {

// Owned particles on the host, sorted by id: every field of
// core/particle_fields.hpp, and the last step's forces.
struct ParticleSnapshot {
  double time = 0;
  long long step = 0;
#define GS_DECLARE_FIELD(name, type, kept) std::vector<type> name;
  GS_PARTICLE_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD
  std::vector<Vec3d> force, torque;
  std::vector<std::uint16_t> contacts;  // occupied history slots; empty without history
  std::size_t size() const { return id.size(); }
};

// The state a run continues from (a checkpoint, read by io/): every particle
// of the run with its history, and the forces of the last step.
struct RestartState {
  long long step = 0;
  double time = 0;
  ParticleRecords particles;
  std::vector<Vec3d> force, torque;  // in `particles` order
  std::optional<InsertionState> insertion;  // a run with inlets: where their insertion stood
};

}  // namespace gs
