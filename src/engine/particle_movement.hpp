#pragma once
// Data movement of one rank's particles, with their last forces and contact
// history: between ranks (messages that comm/ moves), within the store
// (re-sorting, compacting) and between the backend and the host (output,
// checkpoints, restarts). It copies bits and knows no physics: it depends on
// the backend and the force precision only, not on the contact model.
#include <cstdint>
#include <vector>

#include "backend/host_pins.hpp"
#include "core/particle_records.hpp"
#include "core/particle_snapshot.hpp"
#include "engine/particle_message.hpp"
#include "engine/particle_store.hpp"
#include "engine/row_order.hpp"

namespace gs {

class ParticleMovement {
 public:
  virtual ~ParticleMovement() = default;

  // Sizes the force arrays and the contact history for n particles (owned +
  // ghosts); the history grows geometrically and keeps every stored contact.
  virtual void reserve(Index n) = 0;
  // Frees the force arrays' storage, their values spent (a step's kick-drift
  // has read them and its force pass writes every owned particle's anew),
  // until reserve() sizes them again: a list build between the two holds
  // its transients without them (engine/simulation.cpp).
  virtual void release_forces() = 0;

  // Packs particles `which` (store indices in backend memory, as
  // ParticleRouter selects them), with their contact history when
  // `with_history`, into one message in backend memory
  // (engine/particle_message.hpp).
  virtual MessageHeader pack(const ParticleStore& s, const DeviceArray<Index>& which, bool with_history,
                             DeviceArray<unsigned char>& out) const = 0;
  // Appends a message's particles after the current ones, as owned particles
  // with their history (only while there are no ghosts) or as ghosts.
  virtual void unpack(ParticleStore& s, const MessageHeader& h, const unsigned char* payload, bool as_ghosts) = 0;
  // Between rebuilds of the halo: the changing fields a ghost's force partner
  // needs (engine/ghost_forward.hpp) of particles `which`, packed at `out`
  // (backend memory of forward_bytes(which.size(), s.fields_kept)); and the inverse, into
  // the ghosts [first, first + count) that a rebuild's message put there.
  virtual void pack_forward(const ParticleStore& s, const DeviceArray<Index>& which, unsigned char* out) const = 0;
  virtual void unpack_forward(ParticleStore& s, const unsigned char* payload, Index first, Index count) = 0;
  // Keeps the owned particles `keep`, in that order, as [0, keep.size());
  // drops every ghost.
  virtual void keep_owned(ParticleStore& s, const DeviceArray<Index>& keep) = 0;
  // Re-sorts the owned particles (no ghosts) into `order` (store indices, one
  // per owned particle: a cell list's order), forces and history with them.
  virtual void reorder(ParticleStore& s, const DeviceArray<Index>& order) = 0;
  // Appends host particles after the current ones, as unpack() does (a
  // restart's particles).
  virtual void append(ParticleStore& s, const ParticleRecords& r, bool as_ghosts) = 0;
  // Restores the forces and torques of owned particles (store order), as a
  // restart needs them for its first half kick.
  virtual void set_forces(const ParticleStore& s, const std::vector<Vec3d>& force,
                          const std::vector<Vec3d>& torque) = 0;
  virtual void set_history(const ParticleStore& s, const HostHistory& h) = 0;

  // Host copies, owned particles in store order.
  virtual std::vector<Vec3d> forces(const ParticleStore& s) const = 0;
  virtual std::vector<Vec3d> torques(const ParticleStore& s) const = 0;
  HostHistory history(const ParticleStore& s) const {
    HostHistory h;
    HostPins unpinned(false);
    history_to_host(s, RowOrder{}, h, unpinned);
    return h;
  }
  // The owned particles to the host in `order` (engine/row_order.hpp; the
  // default RowOrder: store order): every kept particle field, with_forces
  // the forces and torques in fp64 (zero torques where no effect makes them;
  // else both left empty) and, in runs with contact history, each particle's
  // contacts (occupied slots; output needs these, not the whole history).
  // Each field is put in order on the backend and copied once; `into`'s
  // arrays keep their memory from call to call, `pins` page-locks them.
  virtual void owned_to_host(const ParticleStore& s, const RowOrder& order, ParticleSnapshot& into, HostPins& pins,
                             bool with_forces) const = 0;
  // The same for the contact history (empty rows without history).
  virtual void history_to_host(const ParticleStore& s, const RowOrder& order, HostHistory& into,
                               HostPins& pins) const = 0;
  // The owned particles in ascending id order (engine/owned_id_order.hpp),
  // `storage` (an empty array) holding the order array where the ids are
  // not dense.
  virtual RowOrder owned_row_order(const ParticleStore& s, DeviceArray<Index>& storage) const = 0;
  // Ids and history rows of the owned particles with a stored contact on an
  // analytic wall, in ascending id order: what the wall loads need of the
  // history. As owned_to_host, into arrays kept from call to call (the
  // other fields of `into` left empty).
  virtual void wall_contact_history(const ParticleStore& s, ParticleRecords& into, HostPins& pins) const = 0;

  virtual void synchronize() const = 0;  // waits for the backend's work
  virtual std::size_t bytes() const = 0;  // forces, history and staging
};

}  // namespace gs
