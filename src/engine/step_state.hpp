#pragma once
// What the parts of a step share besides the particle store: the last
// contact forces, the contact history, the fault flag and a staging buffer.
// The force computation writes forces, history and faults; integration reads
// the forces; data movement carries forces and history along with their
// particles. Which history fields exist and whether torques do is decided
// once, by the contact model and effects (contact/contact_models.hpp).
#include "backend/device_array.hpp"
#include "core/fault.hpp"
#include "engine/particle_store.hpp"

namespace gs {

template <class Real>
struct StepState {
  StepState(Backend b, unsigned kept_fields, bool with_torque, int slots)
      : kept(kept_fields), torque(with_torque), fault(b, 1), staging(b) {
    forces.force = DeviceArray<Vec3<Real>>(b);
    forces.torque = DeviceArray<Vec3<Real>>(b);
    history.slots = kept != 0 ? slots : 0;
    history.partner = DeviceArray<ParticleId>(b);
    for_each_history_field(history, [b](const char*, unsigned, auto& a) { a = std::decay_t<decltype(a)>(b); });
    fault.zero();
  }

  bool keeps_history() const { return kept != 0; }

  const unsigned kept;  // HistoryField bits the run keeps (0: no history)
  const bool torque;    // whether an effect makes torques
  ForceArrays<Real> forces;
  ContactHistory<Real> history;
  DeviceArray<Fault> fault;  // the first fault of a step (core/fault.hpp)
  // Reused staging for data movement (reorder, migration, ghosts) and for the
  // cell list's sort keys and second buffers while it is built
  // (neighbor/cell_list.hpp): allocating device memory every step would cost
  // more than the copies, and one buffer for all of them keeps only the
  // largest at the peak. It holds nothing from one call to the next: a user
  // must be done with it (on the stream) before it returns.
  DeviceArray<unsigned char> staging;
};

}  // namespace gs
