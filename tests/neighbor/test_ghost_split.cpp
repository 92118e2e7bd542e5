// The ghost split of the Verlet list (engine/neighbour_finder.hpp,
// GhostSplit): on a store with ghosts, the owned particles with no ghost
// within r_i + r_j + skin (by a brute-force search over the ghosts) come
// first, ascending, then those with one, ascending, each owned particle once;
// a store without ghosts has no split. A rank computes the forces of the
// first while the ghosts' forward is in flight (engine/simulation.cpp), so an
// owned particle with a ghost partner among them would see the ghost's
// previous step (the rank-independence tests, tests/mpi, fail then too).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "backend/cpu/cpu_exec.hpp"
#include "engine/neighbour_finder.hpp"
#include "neighbor/cell_grid.hpp"

namespace gs::test {
namespace {

constexpr double kBox = 0.01, kRadius = 0.0003, kSkin = 0.00006;

// n spheres uniform in the box, the first n_owned owned and the rest ghosts
// (a slab at the top: x_z above 0.8 of the box), ids shuffled.
void fill(ParticleStore& s, Index n_owned, Index n_ghost, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3d> x;
  std::vector<float> r;
  std::vector<ParticleId> id;
  for (Index i = 0; i < n_owned + n_ghost; ++i) {
    const double z = i < n_owned ? 0.8 * u(rng) : 0.8 + 0.2 * u(rng);
    x.push_back({kBox * u(rng), kBox * u(rng), kBox * z});
    r.push_back(float(kRadius * (0.6 + 0.4 * u(rng))));
    id.push_back(ParticleId(i));
  }
  std::shuffle(id.begin(), id.end(), rng);
  s.place_on(Backend::cpu);
  s.n_owned = n_owned;
  s.n_ghost = n_ghost;
  s.position.from_host(x);
  s.radius.from_host(r);
  s.id.from_host(id);
}

bool reaches_a_ghost(const ParticleStore& s, Index i) {
  const std::vector<Vec3d> x = s.position.to_host();
  const std::vector<float> r = s.radius.to_host();
  for (Index j = s.n_owned; j < s.size(); ++j) {
    const double reach = double(r[std::size_t(i)]) + double(r[std::size_t(j)]) + kSkin;
    if (norm2(x[std::size_t(i)] - x[std::size_t(j)]) < reach * reach) return true;
  }
  return false;
}

// The store filled as fill() does, and the neighbour finder's list of it.
struct Built {
  ParticleStore s;
  DeviceArray<unsigned char> scratch{Backend::cpu};
  NeighbourFinder<CpuExec> finder{scratch};
  Built(Index n_owned, Index n_ghost, unsigned seed) {
    fill(s, n_owned, n_ghost, seed);
    finder.build(s, make_cell_grid({0, 0, 0}, {kBox, kBox, kBox}, 2 * kRadius + kSkin), kSkin);
  }
};

TEST(GhostSplit, InteriorFirstThenBoundaryByABruteForceSearch) {
  Built b(12000, 3000, 11);
  const ParticleStore& s = b.s;
  const GhostSplit split = b.finder.ghost_split();
  ASSERT_TRUE(split.valid());
  ASSERT_EQ(split.interior + split.boundary, s.n_owned);
  std::vector<Index> interior, boundary;
  for (Index i = 0; i < s.n_owned; ++i) (reaches_a_ghost(s, i) ? boundary : interior).push_back(i);
  ASSERT_GT(boundary.size(), 100u);  // the slab's neighbourhood: a split worth testing
  ASSERT_GT(interior.size(), 5000u);
  const std::vector<Index> got(split.order, split.order + s.n_owned);
  EXPECT_EQ(std::vector<Index>(got.begin(), got.begin() + split.interior), interior);
  EXPECT_EQ(std::vector<Index>(got.begin() + split.interior, got.end()), boundary);
}

TEST(GhostSplit, NoneWithoutGhosts) {
  Built b(500, 0, 12);
  EXPECT_FALSE(b.finder.ghost_split().valid());
}

}  // namespace
}  // namespace gs::test
