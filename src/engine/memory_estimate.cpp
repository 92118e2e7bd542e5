#include "engine/memory_estimate.hpp"

#include <algorithm>

#include "neighbor/cell_grid.hpp"

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
  m.total_bytes = per * double(scene.particles.size()) + m.cell_bytes;
  return m;
}

}  // namespace gs
