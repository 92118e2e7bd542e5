#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/owner_map.hpp"
#include "core/vec3.hpp"

namespace gs {

// Particles per coarse cell (or per layer of cells). 64-bit so that a global
// count all-reduced over many ranks cannot overflow (MPI_INT64_T on the wire).
using Histogram = std::vector<std::int64_t>;
// One layer histogram per axis x, y, z.
using LayerHistograms = std::array<Histogram, 3>;

// component(v, axis): core/periodic_box.hpp (through core/owner_map.hpp).

// A uniform grid of coarse cells covering the box [lo, hi]. Ownership is
// defined per coarse cell, so every rank must map a point to the same integer
// cell coordinates: coord() uses one fixed formula, floor((p - lo) / edge),
// with no fused or reordered arithmetic, and clamps points outside the box to
// the nearest cell. The grid is a pure function of (lo, hi, min_edge,
// max_cells), so every rank that calls make() with the same arguments builds
// the same grid.
struct CoarseGrid {
  std::array<double, 3> lo{}, hi{};
  std::array<int, 3> dims{1, 1, 1};
  std::array<double, 3> edge{};  // (hi - lo) / dims along each axis

  // Cells of edge >= min_edge * k along every axis that is at least that long,
  // with the smallest integer k >= 1 that keeps the cell count <= max_cells
  // (0: no cap). An axis shorter than min_edge gets one cell (its edge is then
  // the whole extent, which still holds every interaction along that axis).
  static CoarseGrid make(const Vec3d& lo, const Vec3d& hi, double min_edge, std::int64_t max_cells = 0);

  // Integer cell coordinate of p along axis, clamped to [0, dims - 1];
  // NaN maps to 0 so that a corrupt position cannot index out of range.
  int coord(int axis, double p) const;
  std::array<int, 3> coords(const Vec3d& x) const;

  // Linear index, x fastest. Valid for grids whose cell count fits (see n_cells()).
  std::int64_t index(int i, int j, int k) const {
    return i + std::int64_t(dims[0]) * (j + std::int64_t(dims[1]) * k);
  }
  std::int64_t cell_of(const Vec3d& x) const;
  std::int64_t n_cells() const;  // throws std::overflow_error beyond int64
  double min_edge() const;

  // Coordinate of the lower face of cell layer c along axis (for logs and tests;
  // ownership itself never compares coordinates against faces).
  double face(int axis, int c) const { return lo[axis] + c * edge[axis]; }

  // Per-axis ranges [first, last] of the cells that any point (double) of
  // the closed cube of half-width h around x falls into: never misses one
  // (see the .cpp for why rounding cannot shrink the range).
  void cells_near(const Vec3d& x, double h, std::array<int, 3>& first, std::array<int, 3>& last) const;

  // The grid as an owner table's shape, with the given table strides.
  OwnerMapShape owner_map_shape(const std::array<std::int64_t, 3>& stride) const;
};

// Particles per coarse cell, indexed by CoarseGrid::index (for the METIS decomposition).
Histogram cell_histogram(const CoarseGrid& grid, const std::vector<Vec3d>& positions);
// Particles per layer of cells along axis (for the slab decomposition).
Histogram layer_histogram(const CoarseGrid& grid, int axis, const std::vector<Vec3d>& positions);
LayerHistograms layer_histograms(const CoarseGrid& grid, const std::vector<Vec3d>& positions);

}  // namespace gs
