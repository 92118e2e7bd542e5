#pragma once
// Uniform cell grid for the contact search. The cell edge is at least the
// largest particle diameter, so every contact partner of a particle lies in
// its own or one of the 26 surrounding cells. On a periodic axis the cells
// tile the box exactly (the edge stretched to length / cells), and the cells
// beyond either face are those at the other face.
#include <cstdint>

#include "core/hd.hpp"
#include "core/periodic_box.hpp"
#include "core/vec3.hpp"

namespace gs {

struct CellCoord {
  int x, y, z;
};

struct CellGrid {
  Vec3d origin;        // lower corner of cell (0,0,0)
  double cell_size = 1;  // the edge asked for; a periodic axis's may be longer
  double inverse_edge[3] = {1, 1, 1};  // per axis: 1 / the cells' edge
  int dims[3] = {1, 1, 1};
  PeriodicBox box;       // the axes that wrap (none: box.axes == 0)

  GS_HD std::int64_t cell_count() const { return std::int64_t(dims[0]) * dims[1] * dims[2]; }

  // Cell of a point; points outside are clamped to the border cells (their
  // escape is reported by the integrator, not here).
  GS_HD CellCoord coord(const Vec3d& x) const {
    return {clamp_axis((x.x - origin.x) * inverse_edge[0], 0), clamp_axis((x.y - origin.y) * inverse_edge[1], 1),
            clamp_axis((x.z - origin.z) * inverse_edge[2], 2)};
  }
  GS_HD std::int64_t linear(const CellCoord& c) const {
    return (std::int64_t(c.z) * dims[1] + c.y) * dims[0] + c.x;
  }
  GS_HD bool inside(const CellCoord& c) const {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < dims[0] && c.y < dims[1] && c.z < dims[2];
  }

 private:
  GS_HD int clamp_axis(double f, int axis) const {
    int c = f < 0 ? -1 : int(f);
    if (c < 0) c = 0;
    if (c >= dims[axis]) c = dims[axis] - 1;
    return c;
  }
};

// Most cells a grid may have: its tables take 8 bytes a cell, and cell
// indices must stay far inside the int range of the kernels.
constexpr double kMaxGridCells = 2.0e9;

// Cells of the grid over [lo, hi] with cells of edge `cell_size`, counted in
// double so that a huge box gives a huge count instead of an overflow
// (infinite when the extent is).
double grid_cells(const Vec3d& lo, const Vec3d& hi, double cell_size);

// Grid over the box [lo, hi] with cells of edge >= min_cell_size. Throws when
// it would need more than kMaxGridCells cells. On the axes `box` wraps, the
// cells tile [lo, hi) exactly: floor(length / min_cell_size) cells, stretched.
CellGrid make_cell_grid(const Vec3d& lo, const Vec3d& hi, double min_cell_size, const PeriodicBox& box = {});

}  // namespace gs
