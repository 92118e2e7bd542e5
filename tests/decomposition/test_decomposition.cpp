// Coarse grid and slab decomposition. METIS tests: test_metis_decomposition.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "decomposition/slab_cuts.hpp"
#include "decomposition/slab_decomposition.hpp"
#include "decomposition_test_helpers.hpp"

namespace gs {
namespace {

// Optimal largest run load by exhaustive dynamic programming (reference for balanced_cuts).
std::int64_t best_bottleneck(const Histogram& h, int n) {
  const int L = int(h.size());
  const std::int64_t inf = std::numeric_limits<std::int64_t>::max();
  std::vector<std::int64_t> pre(std::size_t(L) + 1, 0);
  for (int i = 0; i < L; ++i) pre[std::size_t(i) + 1] = pre[std::size_t(i)] + h[std::size_t(i)];
  // best[k][c]: first c layers in k non-empty runs.
  std::vector<std::vector<std::int64_t>> best(std::size_t(n) + 1, std::vector<std::int64_t>(std::size_t(L) + 1, inf));
  best[0][0] = 0;
  for (int k = 1; k <= n; ++k)
    for (int c = k; c <= L; ++c)
      for (int s = k - 1; s < c; ++s)
        if (best[std::size_t(k - 1)][std::size_t(s)] != inf)
          best[std::size_t(k)][std::size_t(c)] = std::min(best[std::size_t(k)][std::size_t(c)],
              std::max(best[std::size_t(k - 1)][std::size_t(s)], pre[std::size_t(c)] - pre[std::size_t(s)]));
  return best[std::size_t(n)][std::size_t(L)];
}

std::int64_t max_run(const Histogram& h, const std::vector<int>& b) {
  std::int64_t m = 0;
  for (std::size_t r = 0; r + 1 < b.size(); ++r) {
    std::int64_t s = 0;
    for (int l = b[r]; l < b[r + 1]; ++l) s += h[std::size_t(l)];
    m = std::max(m, s);
  }
  return m;
}

TEST(CoarseGrid, EdgesAtLeastCellSizeAndClamping) {
  const auto g = CoarseGrid::make(Vec3d(0, 0, 0), Vec3d(1, 0.55, 0.05), 0.1);
  EXPECT_EQ(g.dims, (std::array<int, 3>{10, 5, 1}));
  for (int a = 0; a < 2; ++a) EXPECT_GE(g.edge[std::size_t(a)], 0.1);
  EXPECT_EQ(g.coord(0, -5.0), 0);
  EXPECT_EQ(g.coord(0, 7.0), 9);
  EXPECT_EQ(g.coord(0, 1.0), 9);  // the upper face belongs to the last cell
  EXPECT_EQ(g.coord(0, std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(g.coord(1, 0.2), 1);
}

TEST(CoarseGrid, CapOnCellsUsesSmallestIntegerCoarsening) {
  const auto g = CoarseGrid::make(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 0.01, 1000);
  EXPECT_LE(g.n_cells(), 1000);
  EXPECT_EQ(g.dims[0], 10);  // k = 10: (100/10)^3 = 1000; k = 9 gives 11^3
  EXPECT_GE(g.edge[0], 0.01 * 10 * (1 - 1e-12));
  EXPECT_THROW(CoarseGrid::make(Vec3d(0, 0, 0), Vec3d(0, 1, 1), 0.1), std::invalid_argument);
}

TEST(BalancedCuts, SpreadsSlackAtQuantilesAndSplitsEmptyEvenly) {
  EXPECT_EQ(balanced_cuts(Histogram(10, 100), 4), (std::vector<int>{0, 2, 5, 7, 10}));
  EXPECT_EQ(balanced_cuts(Histogram(8, 0), 4), (std::vector<int>{0, 2, 4, 6, 8}));
  EXPECT_EQ(balanced_cuts(Histogram{5, 0, 0, 0, 0, 5}, 2), (std::vector<int>{0, 3, 6}));
  EXPECT_THROW(balanced_cuts(Histogram(3, 1), 4), std::invalid_argument);
}

TEST(BalancedCuts, OptimalOnRandomHistograms) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 400; ++trial) {
    const int L = 1 + int(rng() % 14), n = 1 + int(rng() % std::uint32_t(L));
    Histogram h(static_cast<std::size_t>(L));
    for (auto& c : h) c = (rng() % 3 == 0) ? 0 : std::int64_t(rng() % 50);
    const auto b = balanced_cuts(h, n);
    ASSERT_EQ(b.size(), std::size_t(n) + 1);
    EXPECT_EQ(b.front(), 0);
    EXPECT_EQ(b.back(), L);
    for (int r = 0; r < n; ++r) EXPECT_LT(b[std::size_t(r)], b[std::size_t(r) + 1]) << "slab " << r << " empty";
    EXPECT_EQ(max_run(h, b), best_bottleneck(h, n)) << "trial " << trial;
  }
}

// Slab loads must match counting owner() over the particles, and reach the DP optimum.
void expect_optimal_slabs(const std::vector<Vec3d>& pts, const Vec3d& lo, const Vec3d& hi, double cell, int n) {
  const auto d = SlabDecomposition::from_positions(lo, hi, cell, n, 2, pts);
  std::vector<std::int64_t> counted(std::size_t(n), 0);
  for (const auto& p : pts) ++counted[std::size_t(d.owner(p))];
  EXPECT_EQ(counted, d.loads());
  const Histogram h = layer_histogram(d.grid(), 2, pts);
  const double best = double(best_bottleneck(h, n)) * n / double(pts.size());
  EXPECT_NEAR(d.imbalance(), best, 1e-12) << d.describe();
}

TEST(SlabDecomposition, BalancedOnUniformAndSkewedBeds) {
  const Vec3d lo(0, 0, 0), hi(1, 1, 2);
  const auto uniform = test::uniform_points(100000, lo, hi, 1);
  for (int n : {2, 4, 7}) expect_optimal_slabs(uniform, lo, hi, 0.02, n);
  const auto d = SlabDecomposition::from_positions(lo, hi, 0.02, 4, 2, uniform);
  EXPECT_LT(d.imbalance(), 1.03);

  auto skewed = uniform;  // density ~ z^(-3/4): most particles near the floor
  for (auto& p : skewed) p.z = 2.0 * std::pow(p.z / 2.0, 4);
  for (int n : {3, 6, 12}) expect_optimal_slabs(skewed, lo, hi, 0.02, n);
  const auto s = SlabDecomposition::from_positions(lo, hi, 0.02, 6, 2, skewed);
  EXPECT_LT(s.layer_bounds()[1], 3) << "first slab should be a thin dense layer";
  EXPECT_GT(s.layer_bounds()[5], 40) << "last slab should be a thick sparse region";
}

TEST(SlabDecomposition, OwnerAgreesWithBoundaries) {
  const Vec3d lo(-1, 0, 0), hi(3, 1, 1);
  const auto pts = test::uniform_points(20000, lo, hi, 3);
  const auto d = SlabDecomposition::from_positions(lo, hi, 0.05, 5, 0, pts);
  for (const auto& p : test::uniform_points(20000, lo - Vec3d(1, 1, 1), hi + Vec3d(1, 1, 1), 4)) {
    int expect = 0;
    bool near_face = false;
    for (int r = 1; r < 5; ++r) {
      if (p.x >= d.boundary(r)) expect = r;
      near_face = near_face || std::fabs(p.x - d.boundary(r)) < 1e-9;
    }
    if (near_face) continue;
    ASSERT_EQ(d.owner(p), expect) << "x = " << p.x;
  }
  EXPECT_EQ(d.boundary(0), -1.0);
}

TEST(SlabDecomposition, AutoAxisPicksLongestParticleExtent) {
  const Vec3d lo(0, 0, 0), hi(1, 1, 1);
  auto along_y = test::uniform_points(5000, Vec3d(0.45, 0, 0.4), Vec3d(0.55, 1, 0.6), 5);
  EXPECT_EQ(SlabDecomposition::from_positions(lo, hi, 0.05, 4, -1, along_y).axis(), 1);
  auto along_z = test::uniform_points(5000, Vec3d(0.3, 0.3, 0), Vec3d(0.6, 0.6, 1), 6);
  EXPECT_EQ(SlabDecomposition::from_positions(lo, hi, 0.05, 4, -1, along_z).axis(), 2);
  // Particles longest along x, but x has too few layers for 4 slabs: take the longest axis that fits.
  const auto thin_x = test::uniform_points(5000, Vec3d(0, 0, 0.4), Vec3d(0.3, 0.15, 0.45), 8);
  const auto d = SlabDecomposition::from_positions(lo, Vec3d(0.3, 1, 1), 0.1, 4, -1, thin_x);
  EXPECT_EQ(d.axis(), 1) << d.describe();
}

TEST(SlabDecomposition, TooThinDomainThrowsClearError) {
  const auto pts = test::uniform_points(100, Vec3d(0, 0, 0), Vec3d(1, 1, 0.3), 9);
  try {
    SlabDecomposition::from_positions(Vec3d(0, 0, 0), Vec3d(1, 1, 0.3), 0.1, 4, 2, pts);
    FAIL() << "expected a too-thin error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("too thin for 4 ranks along z"), std::string::npos) << e.what();
  }
  EXPECT_THROW(SlabDecomposition::from_positions(Vec3d(0, 0, 0), Vec3d(0.2, 0.2, 0.2), 0.1, 3, -1, pts),
               std::runtime_error);
}

TEST(SlabDecomposition, BoundsArePureFunctionOfGlobalHistogram) {
  const Vec3d lo(0, 0, 0), hi(1, 1, 1);
  auto pts = test::uniform_points(30000, lo, hi, 10);
  for (auto& p : pts) p.y = p.y * p.y;
  const auto whole = SlabDecomposition::from_positions(lo, hi, 0.02, 6, 1, pts);
  // As a multi-rank run does it: per-"rank" histograms summed (all-reduce).
  std::shuffle(pts.begin(), pts.end(), std::mt19937(11));
  const auto grid = CoarseGrid::make(lo, hi, 0.02);
  Histogram sum(std::size_t(grid.dims[1]), 0);
  for (std::size_t part = 0; part < 3; ++part) {
    const auto first = pts.begin() + std::ptrdiff_t(part * 10000);
    const std::vector<Vec3d> mine(first, first + 10000);
    const Histogram h = layer_histogram(grid, 1, mine);
    for (std::size_t l = 0; l < sum.size(); ++l) sum[l] += h[l];
  }
  const SlabDecomposition reduced(grid, 6, 1, sum);
  EXPECT_EQ(whole.layer_bounds(), reduced.layer_bounds());
}

TEST(SlabDecomposition, RebalanceFollowsTheParticles) {
  const Vec3d lo(0, 0, 0), hi(1, 1, 1);
  auto pts = test::uniform_points(20000, lo, hi, 12);
  auto d = SlabDecomposition::from_positions(lo, hi, 0.02, 4, 2, pts);
  const auto before = d.layer_bounds();
  for (auto& p : pts) p.z = 0.5 + 0.5 * p.z;  // everything moves into the upper half
  d.rebalance(pts);
  EXPECT_NE(d.layer_bounds(), before);
  EXPECT_GE(d.layer_bounds()[1], 30) << "slab 0 should take the empty lower half and a quarter of the rest";
  const Histogram h = layer_histogram(d.grid(), 2, pts);
  EXPECT_NEAR(d.imbalance(), double(best_bottleneck(h, 4)) * 4 / double(pts.size()), 1e-12);
  EXPECT_EQ(d.axis(), 2);
}

TEST(SlabDecomposition, RanksNearIsConservativeAndTight) {
  const Vec3d lo(0, 0, 0), hi(1, 0.4, 0.4);
  const auto pts = test::uniform_points(20000, lo, Vec3d(1, 0.4, 0.1), 13);
  const auto d = SlabDecomposition::from_positions(lo, hi, 0.05, 6, 0, pts);
  const int m = 41;  // lattice spacing 0.025 also hits every cell face
  const auto lat = test::lattice(lo, hi, m);
  const auto q = test::query_points(d.grid(), 150, 14);
  EXPECT_EQ(test::check_ranks_near(d, lat, 1.0 / (m - 1), q, {0.0, 0.01, 0.05, 0.12}), 0);
  EXPECT_EQ(test::check_neighbours(d, q, 0.05), 0);
  EXPECT_EQ(d.neighbours(0), (std::vector<int>{1}));
  EXPECT_EQ(d.neighbours(3), (std::vector<int>{2, 4}));
}

// Smallest double that coord() puts in layer c or above.
double first_double_in_layer(const CoarseGrid& g, int axis, int c) {
  const double inf = std::numeric_limits<double>::infinity();
  double f = g.face(axis, c);
  while (g.coord(axis, f) >= c) f = std::nextafter(f, -inf);
  while (g.coord(axis, f) < c) f = std::nextafter(f, inf);
  return f;
}

// Points x a few ulps either side of face + h: the rank below must be listed
// whenever its last point lies within h of x in exact arithmetic (long double
// holds these differences exactly), and must not be listed once that point
// is clearly (more than an ulp) beyond h.
TEST(SlabDecomposition, RanksNearIsExactAtFaces) {
  const Vec3d lo(0, 0, 0), hi(1, 1, 1);
  const auto d = SlabDecomposition::from_positions(lo, hi, 0.07, 5, 0, test::uniform_points(5000, lo, hi, 16));
  const double inf = std::numeric_limits<double>::infinity();
  int inside = 0, outside = 0, wrong = 0;
  std::vector<int> near;
  for (int r = 1; r < 5; ++r) {
    const double face = first_double_in_layer(d.grid(), 0, d.layer_bounds()[std::size_t(r)]);
    const double below = std::nextafter(face, -inf);  // last point of rank r - 1
    for (double h : {0.0, 0.01, 0.0123456789, 0.07, 0.15}) {
      double x = face + h;
      for (int i = 0; i < 6; ++i) x = std::nextafter(x, -inf);
      for (int step = 0; step < 12; ++step, x = std::nextafter(x, inf)) {
        const Vec3d p(x, 0.5, 0.5);
        if (d.owner(p) < r) continue;
        const long double gap = (long double)x - (long double)below - (long double)h;
        near.clear();
        d.ranks_near(p, h, d.owner(p), near);
        const bool listed = std::find(near.begin(), near.end(), r - 1) != near.end();
        if (gap <= 0) {
          ++inside;
          wrong += !listed;
        } else if (gap > 2.5e-16L) {
          ++outside;
          wrong += listed;
        }
      }
    }
  }
  EXPECT_GT(inside, 20);
  EXPECT_GT(outside, 20);
  EXPECT_EQ(wrong, 0);
}

TEST(SlabDecomposition, OneRankIsTrivial) {
  const auto pts = test::uniform_points(1000, Vec3d(0, 0, 0), Vec3d(1, 1, 1), 15);
  const auto d = SlabDecomposition::from_positions(Vec3d(0, 0, 0), Vec3d(1, 1, 1), 0.5, 1, -1, pts);
  std::vector<int> near;
  d.ranks_near(Vec3d(0.5, 0.5, 0.5), 10.0, 0, near);
  EXPECT_TRUE(near.empty());
  EXPECT_TRUE(d.neighbours(0).empty());
  EXPECT_EQ(d.owner(Vec3d(9, -9, 0.2)), 0);
  EXPECT_DOUBLE_EQ(d.imbalance(), 1.0);
  EXPECT_EQ(d.describe().rfind("slabs along ", 0), 0u);
}

}  // namespace
}  // namespace gs
