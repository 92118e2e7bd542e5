#pragma once
#include "scene/scene.hpp"

namespace gs {

struct MemoryEstimate {
  double bytes_per_particle = 0;  // particle state, forces, history, sort buffers
  double cell_bytes = 0;          // cell tables
  long long cells = 0;
  double mesh_bytes = 0;          // mesh arrays and their binning (a bound, walls/mesh.hpp)
  double mesh_cells = 0;          // cells of the meshes' grids
  double mesh_entries = 0;        // bound on their (cell, triangle) entries
  double total_bytes = 0;
};

// What a run of this scene holds in device memory, by the layout of
// ParticleStore, the force arrays, the contact history, the cell list and the
// meshes with their binning, at the smallest cells a run uses (one largest
// diameter: the most cells).
MemoryEstimate estimate_memory(const SceneSpec& scene);

}  // namespace gs
