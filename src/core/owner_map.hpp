#pragma once
// Who owns which point, in the form the routing kernels read on the device: a
// decomposition's coarse-cell ownership flattened to one table. Slabs give a
// table of layers (the strides of the other axes are 0), METIS one entry per
// coarse cell. comm/ fills it from decomposition/, so the engine knows neither.
#include <array>
#include <cstdint>
#include <vector>

#include "core/coarse_coord.hpp"
#include "core/periodic_box.hpp"
#include "core/vec3.hpp"

namespace gs {

struct OwnerMapShape {
  double lo[3] = {0, 0, 0};
  double edge[3] = {1, 1, 1};
  int dims[3] = {1, 1, 1};
  std::int64_t stride[3] = {0, 0, 0};  // table entry of cell (i, j, k) = i * stride[0] + ...

  PeriodicBox box;  // the axes that wrap: a halo reaches across their faces

  GS_HD int coord(int axis, double p) const { return coarse_coord(p, lo[axis], edge[axis], dims[axis]); }
  GS_HD std::int64_t entry(int i, int j, int k) const { return i * stride[0] + j * stride[1] + k * stride[2]; }

  // The cell ranges [first, last] along `axis` that [p - h, p + h] meets:
  // the interval itself and, on a periodic axis, its parts beyond either face,
  // wrapped to the other. Returns how many (1 to 3); they may overlap.
  GS_HD int ranges_near(int axis, double p, double h, int first[3], int last[3]) const {
    first[0] = coord(axis, p - h);
    last[0] = coord(axis, p + h);
    int n = 1;
    if (!box.wraps(axis)) return n;
    const double l = component(box.length, axis);
    if (p - h < component(box.lo, axis)) {
      first[n] = coord(axis, p - h + l);
      last[n++] = dims[axis] - 1;
    }
    if (p + h >= component(box.hi, axis)) {
      first[n] = 0;
      last[n++] = coord(axis, p + h - l);
    }
    return n;
  }
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
  // [x - h, x + h]^3 falls into, the cube wrapped across periodic faces (a
  // rank once per cell, so possibly repeatedly). Without periodic axes the
  // same range as CoarseGrid::cells_near, which explains why rounding cannot
  // make it miss a cell.
  template <class F>
  GS_HD void for_each_owner_near(const Vec3d& x, double h, const F& f) const {
    int i0[3], i1[3], j0[3], j1[3], k0[3], k1[3];
    const int ni = shape.ranges_near(0, x.x, h, i0, i1), nj = shape.ranges_near(1, x.y, h, j0, j1),
              nk = shape.ranges_near(2, x.z, h, k0, k1);
    for (int c = 0; c < nk; ++c)
      for (int b = 0; b < nj; ++b)
        for (int a = 0; a < ni; ++a)
          for (int k = k0[c]; k <= k1[c]; ++k)
            for (int j = j0[b]; j <= j1[b]; ++j)
              for (int i = i0[a]; i <= i1[a]; ++i) f(owner[shape.entry(i, j, k)]);
  }
};

}  // namespace gs
