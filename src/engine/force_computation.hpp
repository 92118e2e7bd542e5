#pragma once
// Contact forces and torques of the owned particles from the neighbours the
// run's NeighbourSearch found, the analytic walls and the triangle meshes:
// compiled per backend, force precision, contact model and set of effects.
#include <vector>

#include "core/contact_measure.hpp"
#include "engine/neighbour_search.hpp"
#include "engine/particle_store.hpp"
#include "walls/mesh.hpp"
#include "walls/wall.hpp"

namespace gs {

class ForceComputation {
 public:
  virtual ~ForceComputation() = default;

  virtual void set_walls(const std::vector<Wall>& walls) = 0;  // posed
  // Triangle meshes (walls/mesh.hpp): everything once, then the poses each
  // step the meshes move, and the cell bins when rebinned.
  virtual void set_meshes(const MeshSet& meshes) = 0;
  virtual void set_mesh_pose(const MeshSet& meshes) = 0;
  virtual void set_mesh_bins(const MeshBins& bins) = 0;
  // With each build of the neighbour lists, what surfaces each owned particle
  // can touch until the next, at the store's positions and the walls' and
  // meshes' poses: the triangles near it (walls/mesh_near.hpp), and a row of
  // surface slots where a wall or mesh is within reach (engine/surface_rows.hpp).
  virtual void build_surface_lists(const ParticleStore& s, double skin) = 0;

  // Forces, torques and history of every owned particle at the store's state.
  virtual void compute(ParticleStore& s, double dt, long long step) = 0;
  // The same in two parts (Simulation::compute_forces): the interior
  // particles of `split`, which reads nothing of the ghosts, then the
  // boundary ones, once the ghosts hold their fields. Each particle gets the
  // force, torque and history compute() would give it, its sums in the same
  // order.
  virtual void compute_interior(ParticleStore& s, double dt, long long step, const GhostSplit& split) = 0;
  virtual void compute_boundary(ParticleStore& s, double dt, long long step, const GhostSplit& split) = 0;
  // Load of each owned particle (store order) on each mesh, entry
  // i * n_meshes + m, from the last computation; empty without meshes.
  virtual std::vector<MeshLoad> particle_mesh_loads(const ParticleStore& s) const = 0;
  // The measurements' contact pass (engine/contact_measure_kernel.hpp), right
  // after compute() at the same state; then its result per owned particle
  // (store order). Reads the forces' inputs and history, writes neither.
  virtual void measure_contacts(ParticleStore& s, long long step) = 0;
  virtual std::vector<ContactMeasure> contact_measures(const ParticleStore& s) const = 0;
  virtual std::size_t bytes() const = 0;  // pair table, walls, meshes
};

}  // namespace gs
