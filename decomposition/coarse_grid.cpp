#include "coarse_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/coarse_coord.hpp"

namespace gs {
namespace {

// Per-axis cell counts stay well inside int so that index arithmetic and
// METIS's 32-bit idx_t never overflow on one axis.
constexpr double kMaxCellsPerAxis = double(1 << 30);

const char* axis_name(int a) { return a == 0 ? "x" : (a == 1 ? "y" : "z"); }

void check_domain(const Vec3d& lo, const Vec3d& hi, double min_edge, std::int64_t max_cells) {
  if (!(min_edge > 0) || !std::isfinite(min_edge))
    throw std::invalid_argument("CoarseGrid: cell size must be positive and finite, got " + std::to_string(min_edge));
  if (max_cells < 0) throw std::invalid_argument("CoarseGrid: max_cells must be >= 0 (0 = no cap)");
  for (int a = 0; a < 3; ++a) {
    const double l = component(lo, a), h = component(hi, a);
    if (!std::isfinite(l) || !std::isfinite(h) || !(h > l))
      throw std::invalid_argument(std::string("CoarseGrid: domain needs finite lo < hi along ") + axis_name(a));
  }
}

// Largest count d with extent / d >= min_edge (at least 1). The floor is
// corrected downwards because extent / min_edge may round up to an integer.
int base_dim(double extent, double min_edge, int axis) {
  const double d = std::floor(extent / min_edge);
  if (d > kMaxCellsPerAxis)
    throw std::invalid_argument(std::string("CoarseGrid: more than 2^30 cells along ") + axis_name(axis) +
                                "; the cell size is too small for the domain");
  int n = std::max(1, int(d));
  while (n > 1 && extent / n < min_edge) --n;
  return n;
}

// Cell count when every axis is coarsened by the integer factor k. Uses the
// identity floor(x / k) = floor(floor(x) / k) so edges stay >= min_edge * k.
double product_for(const std::array<int, 3>& base, int k) {
  double p = 1;
  for (int a = 0; a < 3; ++a) p *= std::max(1, base[a] / k);
  return p;
}

// Smallest k >= 1 whose cell count is <= max_cells; the count is monotone in k.
int coarsening_factor(const std::array<int, 3>& base, std::int64_t max_cells) {
  if (max_cells == 0 || product_for(base, 1) <= double(max_cells)) return 1;
  int lo = 1, hi = std::max({base[0], base[1], base[2]});  // at hi every axis has one cell
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    if (product_for(base, mid) <= double(max_cells))
      hi = mid;
    else
      lo = mid;
  }
  return hi;
}

}  // namespace

CoarseGrid CoarseGrid::make(const Vec3d& lo, const Vec3d& hi, double min_edge, std::int64_t max_cells) {
  check_domain(lo, hi, min_edge, max_cells);
  CoarseGrid g;
  std::array<int, 3> base{};
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = component(lo, a);
    g.hi[a] = component(hi, a);
    base[a] = base_dim(g.hi[a] - g.lo[a], min_edge, a);
  }
  const int k = coarsening_factor(base, max_cells);
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = std::max(1, base[a] / k);
    g.edge[a] = (g.hi[a] - g.lo[a]) / g.dims[a];
  }
  return g;
}

int CoarseGrid::coord(int axis, double p) const { return coarse_coord(p, lo[axis], edge[axis], dims[axis]); }

std::array<int, 3> CoarseGrid::coords(const Vec3d& x) const {
  return {coord(0, x.x), coord(1, x.y), coord(2, x.z)};
}

std::int64_t CoarseGrid::cell_of(const Vec3d& x) const {
  const auto c = coords(x);
  return index(c[0], c[1], c[2]);
}

std::int64_t CoarseGrid::n_cells() const {
  const double p = double(dims[0]) * double(dims[1]) * double(dims[2]);
  if (p > 9.0e18)
    throw std::overflow_error("CoarseGrid: cell count does not fit in int64; make the grid with max_cells");
  return std::int64_t(dims[0]) * dims[1] * dims[2];
}

double CoarseGrid::min_edge() const { return std::min({edge[0], edge[1], edge[2]}); }

void CoarseGrid::cells_near(const Vec3d& x, double h, std::array<int, 3>& first, std::array<int, 3>& last) const {
  if (!(h >= 0)) throw std::invalid_argument("CoarseGrid::cells_near: halo width must be >= 0");
  for (int a = 0; a < 3; ++a) {
    // No padding is needed: rounding is monotone and every position is a
    // double, so a position q with p - h <= q (exactly) also has
    // fl(p - h) <= q, and coord() is monotone too; likewise at p + h. The
    // range can only gain a cell whose nearest point is a fraction of an ulp
    // beyond h, never lose one.
    const double p = component(x, a);
    first[a] = coord(a, p - h);
    last[a] = coord(a, p + h);
  }
}

OwnerMapShape CoarseGrid::owner_map_shape(const std::array<std::int64_t, 3>& stride) const {
  OwnerMapShape s;
  for (int a = 0; a < 3; ++a) {
    s.lo[a] = lo[a];
    s.edge[a] = edge[a];
    s.dims[a] = dims[a];
    s.stride[a] = stride[a];
  }
  return s;
}

Histogram cell_histogram(const CoarseGrid& grid, const std::vector<Vec3d>& positions) {
  Histogram h(std::size_t(grid.n_cells()), 0);
  for (const Vec3d& x : positions) ++h[std::size_t(grid.cell_of(x))];
  return h;
}

Histogram layer_histogram(const CoarseGrid& grid, int axis, const std::vector<Vec3d>& positions) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("layer_histogram: axis must be 0, 1 or 2");
  Histogram h(std::size_t(grid.dims[axis]), 0);
  for (const Vec3d& x : positions) ++h[std::size_t(grid.coord(axis, component(x, axis)))];
  return h;
}

LayerHistograms layer_histograms(const CoarseGrid& grid, const std::vector<Vec3d>& positions) {
  return {layer_histogram(grid, 0, positions), layer_histogram(grid, 1, positions),
          layer_histogram(grid, 2, positions)};
}

}  // namespace gs
