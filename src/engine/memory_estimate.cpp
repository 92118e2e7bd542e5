#include "engine/memory_estimate.hpp"

#include <algorithm>

#include "neighbor/cell_grid.hpp"
#include "walls/mesh.hpp"

namespace gs {

MemoryEstimate estimate_memory(const SceneSpec& scene) {
  const double real = fp32_forces(scene.precision) ? 4 : 8;
  // id, material, marker, radius, mass, inertia, position, velocity, angular velocity, orientation
  double per = 4 + 1 + 1 + 3 * 4 + 3 * 24 + 16;
  per += 3 * real;                                        // force
  const bool torque = uses_history(scene.effects);
  if (torque) per += 3 * real;                            // torque
  if (uses_history(scene.effects)) {
    double slot = 4;                                      // partner id
    if (scene.effects & kFriction) slot += 3 * real;
    if (scene.effects & kRollingResistance) slot += 3 * real;
    per += slot * scene.contact_slots;
  }
  per += 2 * 8 + 2 * 4;                                   // sort keys and indices, double-buffered
  double r = 0;
  for (const auto& p : scene.particles) r = std::max(r, p.radius);
  MemoryEstimate m;
  m.bytes_per_particle = per;
  if (r > 0) {
    const CellGrid g = make_cell_grid(scene.domain_min, scene.domain_max, 2 * r);
    m.cells = g.cell_count();
    m.cell_bytes = 2.0 * 4 * double(m.cells);
  }
  const MeshSet& meshes = scene.meshes;
  if (r > 0 && meshes.n_meshes() > 0) {
    const MeshBinningSize bins = binning_size(meshes, 2 * r, run_binning(2 * r));
    m.mesh_cells = bins.total_cells();
    m.mesh_entries = bins.total_entries();
    // Per vertex the reference and current pose; per triangle corners, edges,
    // ownership and mesh id; per edge its ends.
    m.mesh_bytes = bins.bytes() + 48.0 * meshes.n_vertices() + 29.0 * meshes.n_triangles() + 8.0 * meshes.n_edges;
  }
  m.total_bytes = per * double(scene.particles.size()) + m.cell_bytes + m.mesh_bytes;
  return m;
}

}  // namespace gs
