#pragma once
// The per-step work of one rank behind one interface. An implementation is
// compiled per backend, force precision, contact model and set of effects;
// make_step_kernels picks the one a scene needs, so effects a scene does not
// use cost neither arithmetic nor memory.
#include <memory>
#include <vector>

#include "core/fault.hpp"
#include "core/materials.hpp"
#include "core/particle_records.hpp"
#include "engine/particle_store.hpp"
#include "engine/particle_message.hpp"
#include "integrate/velocity_verlet.hpp"
#include "neighbor/cell_grid.hpp"
#include "scene/scene.hpp"

namespace gs {

// Wall time per phase [s].
struct StepTimings {
  double integrate = 0, neighbours = 0, forces = 0, exchange = 0;
};

class StepKernels {
 public:
  virtual ~StepKernels() = default;

  // Sizes the force arrays and the contact history for n particles (owned +
  // ghosts); the history grows geometrically and keeps every stored contact.
  virtual void reserve(Index n) = 0;
  virtual void set_walls(const std::vector<Wall>& walls) = 0;
  // Triangle meshes (walls/mesh.hpp): everything once, then the vertices and
  // poses each step the meshes move, and the cell bins when rebinned.
  virtual void set_meshes(const MeshSet& meshes) = 0;
  virtual void set_mesh_pose(const MeshSet& meshes) = 0;
  virtual void set_mesh_bins(const MeshBins& bins) = 0;

  virtual void kick_drift(ParticleStore& s, const IntegrationParams& p) = 0;
  virtual void build_cell_list(ParticleStore& s, const CellGrid& grid) = 0;
  // Whether contacts come from a Verlet list (the CPU) rather than from the
  // cell list every step: the grid's cells must then hold the skin too.
  virtual bool uses_verlet_list() const = 0;
  // What the force computation needs to find contacts: the cell list, and
  // with a Verlet list the list too, of particles within r_i + r_j + skin.
  virtual void build_neighbours(ParticleStore& s, const CellGrid& grid, double skin) = 0;
  // The same for one force computation only (ranks, whose ghosts change every
  // step): the cell list alone; with a Verlet list the force kernel then finds
  // each particle's touching partners in the cells and sums them in ascending
  // id, which is the list's order, without writing a list used once.
  virtual void build_neighbours_for_one_step(ParticleStore& s, const CellGrid& grid) = 0;
  // Whether build_neighbours must run before the next force computation:
  // always without a Verlet list; with one, when the store has changed since
  // the build or a particle has moved more than half the skin.
  virtual bool neighbours_stale(const ParticleStore& s) const = 0;
  virtual void compute_forces(ParticleStore& s, double dt, long long step) = 0;
  virtual void kick(ParticleStore& s, const IntegrationParams& p) = 0;
  // Sets the marker of each owned particle by its side of the plane.
  virtual void mark_by_plane(ParticleStore& s, const MarkingSpec& m) = 0;
  // Reorders owned particles, and their history, by the last cell list.
  virtual void reorder_by_cells(ParticleStore& s) = 0;

  virtual Fault take_fault() = 0;  // and clears it
  virtual void synchronize() = 0;

  // Host copies, owned particles in store order.
  virtual std::vector<Vec3d> forces(const ParticleStore& s) const = 0;
  virtual std::vector<Vec3d> torques(const ParticleStore& s) const = 0;
  virtual HostHistory history(const ParticleStore& s) const = 0;
  // Contacts of each owned particle (occupied history slots, store order);
  // all zero without history. Output needs these, not the whole history.
  virtual std::vector<std::uint16_t> contact_counts(const ParticleStore& s) const = 0;
  // Ids and history rows (store order) of the owned particles with a stored
  // contact on an analytic wall: what the wall loads need of the history.
  virtual ParticleRecords wall_contact_history(const ParticleStore& s) const = 0;
  // Load of each owned particle (store order) on each mesh, entry
  // i * n_meshes + m, from the last force computation; empty without meshes.
  virtual std::vector<MeshLoad> particle_mesh_loads(const ParticleStore& s) const = 0;
  virtual void set_history(const ParticleStore& s, const HostHistory& h) = 0;

  // Data movement between ranks (comm/), with the store indices in backend
  // memory (ParticleRouter selects them there). Packs particles `which`,
  // with their contact history when `with_history`, into one message in
  // backend memory (engine/particle_message.hpp); unpack() appends a
  // message's particles after the current ones, as owned particles with
  // their history (only while there are no ghosts) or as ghosts.
  virtual MessageHeader pack(const ParticleStore& s, const DeviceArray<Index>& which, bool with_history,
                             DeviceArray<unsigned char>& out) const = 0;
  virtual void unpack(ParticleStore& s, const MessageHeader& h, const unsigned char* payload, bool as_ghosts) = 0;
  // Keeps the owned particles `keep`, in that order, as [0, keep.size());
  // drops every ghost.
  virtual void keep_owned(ParticleStore& s, const DeviceArray<Index>& keep) = 0;
  // Appends host particles after the current ones, as unpack() does (a
  // restart's particles).
  virtual void append(ParticleStore& s, const ParticleRecords& r, bool as_ghosts) = 0;
  // Restores the forces and torques of owned particles (store order), as a
  // restart needs them for its first half kick.
  virtual void set_forces(const ParticleStore& s, const std::vector<Vec3d>& force,
                          const std::vector<Vec3d>& torque) = 0;

  virtual std::size_t bytes() const = 0;  // memory held by forces, history, cell and Verlet lists
};

struct KernelChoice {
  Backend backend;
  Precision precision;
  ContactModel model;
  unsigned effects;
};

// The kernels of `choice` for the scene's materials and pairs (the pair table
// in force precision is built from them by the chosen contact model).
struct ContactInputs {
  const std::vector<MaterialSpec>& materials;
  const std::vector<PairSpec>& pairs;
  int contact_slots;
};
std::unique_ptr<StepKernels> make_step_kernels(const KernelChoice& choice, const ContactInputs& contacts);
std::unique_ptr<StepKernels> make_step_kernels_cpu(const KernelChoice& choice, const ContactInputs& contacts);
std::unique_ptr<StepKernels> make_step_kernels_cuda(const KernelChoice& choice, const ContactInputs& contacts);

}  // namespace gs
