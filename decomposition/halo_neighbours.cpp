#include "decomposition/halo_neighbours.hpp"

#include <algorithm>
#include <stdexcept>

namespace gs {

std::vector<std::vector<int>> halo_neighbours(const OwnerMapHost& map, double halo, int ranks) {
  const OwnerMapShape& s = map.shape;
  const OwnerMap view{s, map.owner.data()};
  // An axis the table does not vary along (stride 0: a slab's other axes)
  // needs one cell; on the others a cube of half-width h around a cell's
  // centre holds every point within `halo` of the cell.
  int n[3];
  double h = halo;
  for (int a = 0; a < 3; ++a) {
    n[a] = s.stride[a] == 0 ? 1 : s.dims[a];
    if (s.stride[a] != 0) h = std::max(h, 0.5 * s.edge[a] + halo);
  }
  const std::size_t n_ranks = static_cast<std::size_t>(ranks);
  std::vector<std::vector<char>> near(n_ranks, std::vector<char>(n_ranks, 0));
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const int r = map.owner.at(std::size_t(s.entry(i, j, k)));
        if (r < 0 || r >= ranks) throw std::logic_error("halo_neighbours: a cell's owner is not a rank");
        const Vec3d centre(s.lo[0] + (i + 0.5) * s.edge[0], s.lo[1] + (j + 0.5) * s.edge[1],
                           s.lo[2] + (k + 0.5) * s.edge[2]);
        view.for_each_owner_near(centre, h, [&](int q) {
          near[std::size_t(r)][std::size_t(q)] = 1;
          near[std::size_t(q)][std::size_t(r)] = 1;  // symmetric whatever the rounding
        });
      }
  std::vector<std::vector<int>> out(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r)
    for (int q = 0; q < ranks; ++q)
      if (q != r && near[std::size_t(r)][std::size_t(q)]) out[std::size_t(r)].push_back(q);
  return out;
}

}  // namespace gs
