#include "decomposition/owned_bounds.hpp"

#include <limits>

namespace gs {

void owned_bounds(const Decomposition& d, int rank, Vec3d& lo, Vec3d& hi) {
  const CoarseGrid& g = d.grid();
  const double inf = std::numeric_limits<double>::infinity();
  std::array<int, 3> first{g.dims[0], g.dims[1], g.dims[2]}, last{-1, -1, -1};
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        // A cell's centre lies in that cell by coord()'s formula.
        const Vec3d centre(g.lo[0] + (i + 0.5) * g.edge[0], g.lo[1] + (j + 0.5) * g.edge[1],
                           g.lo[2] + (k + 0.5) * g.edge[2]);
        if (d.owner(centre) != rank) continue;
        const int c[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          first[std::size_t(a)] = std::min(first[std::size_t(a)], c[a]);
          last[std::size_t(a)] = std::max(last[std::size_t(a)], c[a]);
        }
      }
  double l[3], h[3];
  for (std::size_t a = 0; a < 3; ++a) {
    l[a] = first[a] == 0 ? -inf : g.face(int(a), first[a]);
    h[a] = last[a] == g.dims[a] - 1 ? inf : g.face(int(a), last[a] + 1);
    if (last[a] < first[a]) l[a] = inf, h[a] = -inf;  // owns nothing
  }
  lo = Vec3d(l[0], l[1], l[2]);
  hi = Vec3d(h[0], h[1], h[2]);
}

}  // namespace gs
