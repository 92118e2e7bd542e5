#include "neighbor/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace gs {

namespace {

// Cells along one axis of extent `extent`, in double: converting first would
// overflow the int for a huge extent.
double axis_cells(double extent, double cell_size) { return std::max(1.0, std::ceil(extent / cell_size)); }

}  // namespace

double grid_cells(const Vec3d& lo, const Vec3d& hi, double cell_size) {
  return axis_cells(hi.x - lo.x, cell_size) * axis_cells(hi.y - lo.y, cell_size) * axis_cells(hi.z - lo.z, cell_size);
}

CellGrid make_cell_grid(const Vec3d& lo, const Vec3d& hi, double min_cell_size, const PeriodicBox& box) {
  if (!(min_cell_size > 0)) throw std::invalid_argument("cell size must be positive");
  const double cells = grid_cells(lo, hi, min_cell_size);
  // !(<=) also refuses an infinite or NaN count.
  if (!(cells <= kMaxGridCells)) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", cells);
    throw std::runtime_error(std::string("the cell grid would need ") + count + " cells of " +
                             std::to_string(min_cell_size) +
                             " m (domain too large for the particle size): shrink the domain");
  }
  CellGrid g;
  g.origin = lo;
  g.cell_size = min_cell_size;
  g.box = box;
  const double extent[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  for (int a = 0; a < 3; ++a) {
    g.inverse_edge[a] = 1.0 / min_cell_size;
    g.dims[a] = int(axis_cells(extent[a], min_cell_size));
    if (box.wraps(a)) {
      // Whole cells only, none narrower than asked: a partner across the
      // face then lies in the first or last cell, never one further.
      g.dims[a] = int(std::max(1.0, std::floor(extent[a] / min_cell_size)));
      g.inverse_edge[a] = double(g.dims[a]) / extent[a];
    }
  }
  return g;
}

}  // namespace gs
