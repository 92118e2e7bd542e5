#pragma once
#include "scene/scene.hpp"

namespace gs {

struct MemoryEstimate {
  double bytes_per_particle = 0;  // particle state, forces, history, sort buffers
  double cell_bytes = 0;          // cell tables
  long long cells = 0;
  double total_bytes = 0;
};

// What a run of this scene holds in device memory, by the layout of
// ParticleStore, the force arrays, the contact history and the cell list.
MemoryEstimate estimate_memory(const SceneSpec& scene);

}  // namespace gs
