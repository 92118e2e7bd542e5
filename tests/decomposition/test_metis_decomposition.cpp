// METIS decomposition of coarse cells. Slab and grid tests: test_decomposition.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <stdexcept>

#include "decomposition/metis_decomposition.hpp"
#include "decomposition_test_helpers.hpp"

namespace gs {
namespace {

const Vec3d kLo(-1, -1, 0), kHi(1, 1, 0.2);
constexpr double kCell = 0.05;  // 40 x 40 x 4 coarse cells

const std::vector<Vec3d>& annulus() {
  static const auto pts = test::annulus_points(200000, 0.5, 0.9, 0.2, 21);
  return pts;
}

// Neighbour sets computed independently: owners of 26-adjacent cells.
std::vector<std::set<int>> adjacent_owners(const MetisDecomposition& d) {
  const CoarseGrid& g = d.grid();
  std::vector<std::set<int>> adj(std::size_t(d.n_ranks()));
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int a = i + dx, b = j + dy, c = k + dz;
              if (a < 0 || b < 0 || c < 0 || a >= g.dims[0] || b >= g.dims[1] || c >= g.dims[2]) continue;
              const int p = d.cell_owner()[std::size_t(g.index(i, j, k))];
              const int q = d.cell_owner()[std::size_t(g.index(a, b, c))];
              if (p != q) adj[std::size_t(p)].insert(q);
            }
  return adj;
}

TEST(MetisDecomposition, AnnulusEveryCellOwnedAndBalanced) {
  for (int n : {3, 4}) {
    const auto d = MetisDecomposition::from_positions(kLo, kHi, kCell, n, annulus());
    ASSERT_EQ(d.cell_owner().size(), std::size_t(d.grid().n_cells()));
    std::vector<int> cells(std::size_t(n), 0);
    for (int p : d.cell_owner()) {
      ASSERT_GE(p, 0);
      ASSERT_LT(p, n);
      ++cells[std::size_t(p)];
    }
    for (int r = 0; r < n; ++r) EXPECT_GT(cells[std::size_t(r)], 0) << "rank " << r << " owns no cell";
    std::vector<std::int64_t> counted(std::size_t(n), 0);
    for (const auto& x : annulus()) ++counted[std::size_t(d.owner(x))];
    EXPECT_EQ(counted, d.loads());
    EXPECT_LT(d.imbalance(), 1.1) << d.describe();
    EXPECT_GE(d.imbalance(), 1.0);
  }
}

TEST(MetisDecomposition, DeterministicAcrossCallsAndRebalance) {
  const auto a = MetisDecomposition::from_positions(kLo, kHi, kCell, 4, annulus());
  const auto b = MetisDecomposition::from_positions(kLo, kHi, kCell, 4, annulus());
  EXPECT_EQ(a.cell_owner(), b.cell_owner());
  auto c = MetisDecomposition::from_positions(kLo, kHi, kCell, 4, annulus());
  c.rebalance(annulus());
  EXPECT_EQ(a.cell_owner(), c.cell_owner());
  // A different seed is allowed to differ but must still be a valid partition.
  const auto e =
      MetisDecomposition::from_positions(kLo, kHi, kCell, 4, annulus(), MetisDecomposition::kDefaultMaxCells, 99);
  EXPECT_LT(e.imbalance(), 1.1);
}

TEST(MetisDecomposition, NeighboursSymmetricAndMatchAdjacentCells) {
  for (int n : {2, 3, 4, 7}) {
    const auto d = MetisDecomposition::from_positions(kLo, kHi, kCell, n, annulus());
    const auto ref = adjacent_owners(d);
    for (int r = 0; r < n; ++r) {
      const auto nb = d.neighbours(r);
      EXPECT_EQ(std::set<int>(nb.begin(), nb.end()), ref[std::size_t(r)]) << "rank " << r << " of " << n;
      EXPECT_TRUE(std::is_sorted(nb.begin(), nb.end()));
    }
    EXPECT_EQ(test::check_neighbours(d, test::query_points(d.grid(), 300, 22), kCell), 0);
  }
}

TEST(MetisDecomposition, EdgeAndCornerContactsAreNeighbours) {
  // 2 x 2 x 1 cells: ranks 0 and 2 touch only at a corner line, like parts meeting diagonally.
  const CoarseGrid g = CoarseGrid::make(Vec3d(0, 0, 0), Vec3d(2, 2, 1), 1.0);
  const auto d = MetisDecomposition::from_cell_owner(g, 3, {0, 1, 1, 2}, Histogram(4, 1));
  EXPECT_EQ(d.neighbours(0), (std::vector<int>{1, 2}));
  EXPECT_EQ(d.neighbours(2), (std::vector<int>{0, 1}));
  std::vector<int> near;
  d.ranks_near(Vec3d(0.95, 0.95, 0.5), 0.1, 0, near);
  std::sort(near.begin(), near.end());
  EXPECT_EQ(near, (std::vector<int>{1, 2}));
  // Scattered owners: every kind of contact, checked against brute force.
  const CoarseGrid g3 = CoarseGrid::make(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 0.25);
  std::mt19937 rng(27);
  std::vector<int> owner(std::size_t(g3.n_cells()));
  for (auto& o : owner) o = int(rng() % 5);
  const auto r = MetisDecomposition::from_cell_owner(g3, 5, owner, Histogram(owner.size(), 1));
  const auto ref = adjacent_owners(r);
  for (int k = 0; k < 5; ++k) {
    const auto nb = r.neighbours(k);
    EXPECT_EQ(std::set<int>(nb.begin(), nb.end()), ref[std::size_t(k)]);
  }
  EXPECT_EQ(test::check_neighbours(r, test::query_points(g3, 300, 28), 0.25), 0);
  const auto lat = test::lattice(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 21);
  EXPECT_EQ(test::check_ranks_near(r, lat, 0.05, test::query_points(g3, 60, 29), {0.0, 0.1, 0.25}), 0);
}

TEST(MetisDecomposition, HandlesMoreThanTwoNeighbours) {
  const Vec3d lo(0, 0, 0), hi(1, 1, 1);
  const auto pts = test::uniform_points(50000, lo, hi, 23);
  const auto d = MetisDecomposition::from_positions(lo, hi, 0.05, 8, pts);
  std::size_t most = 0;
  for (int r = 0; r < 8; ++r) most = std::max(most, d.neighbours(r).size());
  EXPECT_GE(most, 3u) << d.describe();
  EXPECT_LT(d.imbalance(), 1.1);
}

TEST(MetisDecomposition, RanksNearIsConservativeAndTight) {
  const Vec3d lo(-1, -1, 0), hi(1, 1, 0.4);
  const auto pts = test::annulus_points(40000, 0.3, 0.9, 0.4, 24);
  const auto d = MetisDecomposition::from_positions(lo, hi, 0.1, 5, pts);
  const int m = 41;  // spacing 0.05 in x, y: hits every cell face
  const auto lat = test::lattice(lo, hi, m);
  const auto q = test::query_points(d.grid(), 120, 25);
  EXPECT_EQ(test::check_ranks_near(d, lat, 2.0 / (m - 1), q, {0.0, 0.03, 0.1, 0.25}), 0);
}

TEST(MetisDecomposition, CoarsensToCellCap) {
  const auto d = MetisDecomposition::from_positions(kLo, kHi, 0.005, 4, annulus(), 20000);
  EXPECT_LE(d.grid().n_cells(), 20000);
  for (int a = 0; a < 3; ++a) EXPECT_GE(d.grid().edge[std::size_t(a)], 0.005);
  EXPECT_LT(d.imbalance(), 1.1);
}

TEST(MetisDecomposition, ContactLoadShiftsCellsAway) {
  const Vec3d lo(0, 0, 0), hi(1, 0.5, 0.5);
  const auto pts = test::uniform_points(40000, lo, hi, 26);
  const CoarseGrid g = CoarseGrid::make(lo, hi, 0.05, MetisDecomposition::kDefaultMaxCells);
  const Histogram counts = cell_histogram(g, pts);
  Histogram load(counts.size(), 0);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0] / 4; ++i) load[std::size_t(g.index(i, j, k))] = 200;  // heavy contacts at x < 0.25
  const MetisDecomposition plain(g, 2, counts);
  const MetisDecomposition loaded(g, 2, counts, load);
  const int hot = loaded.owner(Vec3d(0.1, 0.25, 0.25));
  EXPECT_LT(loaded.loads()[std::size_t(hot)], loaded.loads()[std::size_t(1 - hot)]);
  EXPECT_GT(loaded.imbalance(), plain.imbalance());
}

TEST(MetisDecomposition, AdoptsAPartitionComputedElsewhere) {
  const auto d = MetisDecomposition::from_positions(kLo, kHi, kCell, 3, annulus());
  const auto copy =
      MetisDecomposition::from_cell_owner(d.grid(), 3, d.cell_owner(), cell_histogram(d.grid(), annulus()));
  EXPECT_EQ(copy.cell_owner(), d.cell_owner());
  EXPECT_EQ(copy.loads(), d.loads());
  EXPECT_EQ(copy.neighbours(1), d.neighbours(1));
  std::vector<int> bad = d.cell_owner();
  bad[0] = 3;
  EXPECT_THROW(MetisDecomposition::from_cell_owner(d.grid(), 3, bad, cell_histogram(d.grid(), annulus())),
               std::invalid_argument);
}

TEST(MetisDecomposition, OneRankIsTrivialAndBadInputsThrow) {
  const auto d = MetisDecomposition::from_positions(kLo, kHi, kCell, 1, annulus());
  EXPECT_TRUE(std::all_of(d.cell_owner().begin(), d.cell_owner().end(), [](int p) { return p == 0; }));
  EXPECT_EQ(d.owner(Vec3d(5, 5, 5)), 0);
  EXPECT_TRUE(d.neighbours(0).empty());
  std::vector<int> near;
  d.ranks_near(Vec3d(0, 0, 0.1), 1.0, 0, near);
  EXPECT_TRUE(near.empty());
  EXPECT_DOUBLE_EQ(d.imbalance(), 1.0);
  EXPECT_THROW(d.neighbours(1), std::out_of_range);
  const CoarseGrid g = CoarseGrid::make(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 0.5);  // 8 cells
  EXPECT_THROW(MetisDecomposition(g, 9, Histogram(8, 1)), std::invalid_argument);
  EXPECT_THROW(MetisDecomposition(g, 2, Histogram(7, 1)), std::invalid_argument);
  EXPECT_THROW(MetisDecomposition(g, 2, Histogram(8, 1), Histogram(3, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace gs
