#include "neighbor/cell_grid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gs {

CellGrid make_cell_grid(const Vec3d& lo, const Vec3d& hi, double min_cell_size) {
  if (!(min_cell_size > 0)) throw std::invalid_argument("cell size must be positive");
  CellGrid g;
  g.origin = lo;
  g.cell_size = min_cell_size;
  g.inverse_cell_size = 1.0 / min_cell_size;
  const double extent[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  double cells = 1;
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = std::max(1, int(std::ceil(extent[a] / min_cell_size)));
    cells *= g.dims[a];
  }
  if (cells > 2.0e9)
    throw std::runtime_error("the cell grid would need " + std::to_string(cells) +
                             " cells (domain too large for the particle size): shrink the domain");
  return g;
}

}  // namespace gs
