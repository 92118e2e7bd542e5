// Ranks that trade ghosts, from the ownership table: with a periodic axis the
// halo reaches across its faces, so the last slab along it neighbours the
// first, and a point near one face is a ghost of the rank at the other.
#include <gtest/gtest.h>

#include <algorithm>

#include "decomposition/halo_neighbours.hpp"
#include "decomposition/slab_decomposition.hpp"

namespace gs {
namespace {

// Four slabs of three layers each along x over [0, 12) (layers of 1), cells of 1.
OwnerMapHost four_slabs(unsigned periodic_axes) {
  OwnerMapHost m;
  m.shape.dims[0] = 12;
  m.shape.stride[0] = 1;
  m.shape.lo[0] = 0;
  m.shape.edge[0] = 1;
  m.shape.dims[1] = m.shape.dims[2] = 4;  // the table does not vary along y, z
  m.shape.box = make_periodic_box(periodic_axes, {0, 0, 0}, {12, 4, 4});
  for (int i = 0; i < 12; ++i) m.owner.push_back(i / 3);
  return m;
}

TEST(HaloNeighbours, SlabsAlongAPeriodicAxisWrap) {
  const auto open = halo_neighbours(four_slabs(0), 1.0, 4);
  EXPECT_EQ(open[0], (std::vector<int>{1}));
  EXPECT_EQ(open[3], (std::vector<int>{2}));
  const auto wrapped = halo_neighbours(four_slabs(1u), 1.0, 4);
  EXPECT_EQ(wrapped[0], (std::vector<int>{1, 3}));
  EXPECT_EQ(wrapped[1], (std::vector<int>{0, 2}));
  EXPECT_EQ(wrapped[3], (std::vector<int>{0, 2}));
  // Wrapping another axis than the slabs' changes nothing.
  EXPECT_EQ(halo_neighbours(four_slabs(2u), 1.0, 4), open);
}

TEST(HaloNeighbours, GhostOwnersReachAcrossThePeriodicFace) {
  const OwnerMapHost m = four_slabs(1u);
  const OwnerMap view{m.shape, m.owner.data()};
  auto owners_near = [&](Vec3d x) {
    std::vector<int> r;
    view.for_each_owner_near(x, 1.0, [&](int q) {
      if (std::find(r.begin(), r.end(), q) == r.end()) r.push_back(q);
    });
    std::sort(r.begin(), r.end());
    return r;
  };
  EXPECT_EQ(owners_near({0.5, 2, 2}), (std::vector<int>{0, 3}));   // across the min face: the last slab
  EXPECT_EQ(owners_near({11.5, 2, 2}), (std::vector<int>{0, 3}));  // across the max face: the first
  EXPECT_EQ(owners_near({6, 2, 2}), (std::vector<int>{1, 2}));     // inside: no wrap
  const OwnerMapHost open = four_slabs(0);
  const OwnerMap open_view{open.shape, open.owner.data()};
  std::vector<int> r;
  open_view.for_each_owner_near({0.5, 2, 2}, 1.0, [&](int q) { r.push_back(q); });
  EXPECT_EQ(std::count(r.begin(), r.end(), 3), 0);
}

}  // namespace
}  // namespace gs
