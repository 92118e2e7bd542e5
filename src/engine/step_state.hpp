#pragma once
// What the parts of a step share besides the particle store: the last
// contact forces, the contact history (of particle pairs and of surfaces),
// the fault flag and a staging buffer.
// The force computation writes forces, history and faults; integration reads
// the forces; data movement carries forces and history along with their
// particles. Which history fields exist and whether torques do is decided
// once, by the contact model and effects (contact/contact_models.hpp).
#include "backend/device_array.hpp"
#include "core/fault.hpp"
#include "engine/pair_history.hpp"
#include "engine/particle_store.hpp"

namespace gs {

template <class Real>
struct StepState {
  // contact_slots: the width of a particle's row of contacts in messages and
  // checkpoints; surface_slots: the slots for walls and mesh features.
  StepState(Backend b, unsigned kept_fields, bool with_torque, int contact_slots, int surface_slots)
      : kept(kept_fields), torque(with_torque), row_width(kept_fields != 0 ? contact_slots : 0), pairs(b),
        fault(b, 1), staging(b) {
    forces.force = DeviceArray<Vec3<Real>>(b);
    forces.torque = DeviceArray<Vec3<Real>>(b);
    history.slots = kept != 0 ? surface_slots : 0;
    history.place_on(b);
    fault.zero();
  }

  bool keeps_history() const { return kept != 0; }

  const unsigned kept;    // HistoryField bits the run keeps (0: no history)
  const bool torque;      // whether an effect makes torques
  const int row_width;    // contacts in a particle's row (contact_slots; 0 without history)
  ForceArrays<Real> forces;
  ContactHistory<Real> history;  // walls and mesh features (surface_slots per row, rows where needed)
  PairHistory<Real> pairs;       // particle pairs, per Verlet list entry (engine/pair_history.hpp)
  DeviceArray<Fault> fault;  // the first fault of a step (core/fault.hpp)
  // Reused staging for data movement (reorder, migration, ghosts) and for the
  // cell list's sort keys and second buffers while it is built
  // (neighbor/cell_list.hpp): allocating device memory every step would cost
  // more than the copies, and one buffer for all of them keeps only the
  // largest at the peak. It holds nothing from one call to the next: a user
  // must be done with it (on the stream) before it returns. A build of the
  // lists frees it before the pair history keeps its contacts and after the
  // sort (engine/neighbour_finder.hpp), so that it stands beside neither the
  // kept contacts nor the new list.
  DeviceArray<unsigned char> staging;
};

}  // namespace gs
