#pragma once
// Who owns which point, in the form the routing kernels read on the device: a
// decomposition's coarse-cell ownership flattened to one table. Slabs give a
// table of layers (the strides of the other axes are 0), METIS one entry per
// coarse cell. comm/ fills it from decomposition/, so the engine knows neither.
#include <array>
#include <cstdint>
#include <vector>

#include "core/coarse_coord.hpp"
#include "core/vec3.hpp"

namespace gs {

struct OwnerMapShape {
  double lo[3] = {0, 0, 0};
  double edge[3] = {1, 1, 1};
  int dims[3] = {1, 1, 1};
  std::int64_t stride[3] = {0, 0, 0};  // table entry of cell (i, j, k) = i * stride[0] + ...

  GS_HD int coord(int axis, double p) const { return coarse_coord(p, lo[axis], edge[axis], dims[axis]); }
  GS_HD std::int64_t entry(int i, int j, int k) const { return i * stride[0] + j * stride[1] + k * stride[2]; }
};

struct OwnerMapHost {
  OwnerMapShape shape;
  std::vector<int> owner;  // rank of each table entry
};

// Device view: the shape and the table in backend memory.
struct OwnerMap {
  OwnerMapShape shape;
  const int* owner;

  GS_HD int owner_of(const Vec3d& x) const {
    return owner[shape.entry(shape.coord(0, x.x), shape.coord(1, x.y), shape.coord(2, x.z))];
  }

  // Calls f(rank) for the owner of every cell that a point of the cube
  // [x - h, x + h]^3 falls into (a rank once per cell, so possibly repeatedly).
  // The same range as CoarseGrid::cells_near, which explains why rounding
  // cannot make it miss a cell.
  template <class F>
  GS_HD void for_each_owner_near(const Vec3d& x, double h, const F& f) const {
    const int i0 = shape.coord(0, x.x - h), i1 = shape.coord(0, x.x + h);
    const int j0 = shape.coord(1, x.y - h), j1 = shape.coord(1, x.y + h);
    const int k0 = shape.coord(2, x.z - h), k1 = shape.coord(2, x.z + h);
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) f(owner[shape.entry(i, j, k)]);
  }
};

}  // namespace gs
