// The Verlet list (neighbor/verlet_list.hpp): it holds exactly the pairs a
// brute-force search finds within r_i + r_j + skin, in ascending id; it goes
// stale when a particle has moved more than half the skin (both checked on
// the CPU's list, the build the GPU's follows); and on every backend a run's
// forces are those of a brute-force search after many rebuilds, and its
// result does not depend on when the list is rebuilt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "backend/cpu/cpu_exec.hpp"
#include "support/support.hpp"
#include "support/thread_lanes.hpp"

namespace gs::test {
namespace {

constexpr double kLarge = 0.001, kSmall = 0.0002;  // radii: 1:5 diameters

struct Cloud {
  std::vector<Vec3d> position;
  std::vector<float> radius;
  std::vector<ParticleId> id;
};

// n spheres uniform in a cube of edge `box`, one in ten large, ids shuffled.
Cloud random_cloud(int n, double box, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(0, box);
  Cloud c;
  for (int i = 0; i < n; ++i) {
    c.position.push_back({coordinate(rng), coordinate(rng), coordinate(rng)});
    c.radius.push_back(float(i % 10 == 0 ? kLarge : kSmall));
    c.id.push_back(ParticleId(i));
  }
  std::shuffle(c.id.begin(), c.id.end(), rng);
  return c;
}

struct BuiltList {
  CellList cells{Backend::cpu};
  DeviceArray<unsigned char> scratch{Backend::cpu};  // the sort buffers
  VerletList list{Backend::cpu};
  DeviceArray<Vec3d> position{Backend::cpu};
  DeviceArray<float> radius{Backend::cpu};
  DeviceArray<ParticleId> id{Backend::cpu};
};

// The list of the first n_owned of the cloud, the others acting as ghosts.
void build(BuiltList& b, const Cloud& c, Index n_owned, double skin, double box) {
  b.position.from_host(c.position);
  b.radius.from_host(c.radius);
  b.id.from_host(c.id);
  const Index n = Index(c.position.size());
  const CellGrid grid = make_cell_grid({0, 0, 0}, {box, box, box}, 2 * kLarge + skin);
  build_cells<CpuExec>(b.cells, b.position.data(), b.id.data(), n, grid, b.scratch);
  build_verlet_list<CpuExec>(b.list, b.cells, b.position.data(), b.radius.data(), b.id.data(), n_owned, n, skin);
  set_list_references<CpuExec>(b.list, b.position.data());
}

TEST(VerletList, HoldsExactlyThePairsWithinTheSkinInIdOrder) {
  const double box = 0.012, skin = 0.0002;
  const Cloud c = random_cloud(6000, box, 7);
  const Index n_owned = 5000;  // the last 1000 stand for ghosts: partners, not list owners
  BuiltList b;
  build(b, c, n_owned, skin, box);
  const std::vector<ListOffset> begin = b.list.begin.to_host();
  const std::vector<Index> list = b.list.list.to_host();
  ASSERT_EQ(begin.size(), std::size_t(n_owned) + 1);
  long long pairs = 0, large_small = 0;
  for (Index i = 0; i < n_owned; ++i) {
    std::vector<Index> expected;
    for (Index j = 0; j < Index(c.position.size()); ++j) {
      const double reach = double(c.radius[i]) + double(c.radius[j]) + skin;
      if (j != i && norm2(c.position[i] - c.position[j]) < reach * reach) expected.push_back(j);
    }
    std::sort(expected.begin(), expected.end(), [&](Index a, Index b2) { return c.id[a] < c.id[b2]; });
    const std::vector<Index> got(list.begin() + begin[i], list.begin() + begin[i + 1]);
    ASSERT_EQ(got, expected) << "particle " << i;
    pairs += Index(got.size());
    for (Index j : got) large_small += c.radius[i] != c.radius[j];
  }
  EXPECT_GT(pairs, 3000);  // a test with neighbours to find, of both sizes
  EXPECT_GT(large_small, 300);
}

// A GPU's cell sort keys the cells alone (CudaExec::cell_keys_hold_ids): a
// cell's particles then come in memory order, not by id. The cells and the
// list built that way on the CPU: every particle in its cell's range, and
// the list the one from keys with ids.
struct CpuExecCellsAlone : CpuExec {
  static constexpr bool cell_keys_hold_ids = false;
};

TEST(VerletList, CellKeysWithoutIdsGiveTheSameList) {
  const double box = 0.012, skin = 0.0002;
  const Cloud c = random_cloud(6000, box, 9);
  const Index n = Index(c.position.size());
  BuiltList with_ids;
  build(with_ids, c, n, skin, box);
  BuiltList alone;
  alone.position.from_host(c.position);
  alone.radius.from_host(c.radius);
  alone.id.from_host(c.id);
  const CellGrid grid = make_cell_grid({0, 0, 0}, {box, box, box}, 2 * kLarge + skin);
  build_cells<CpuExecCellsAlone>(alone.cells, alone.position.data(), alone.id.data(), n, grid, alone.scratch);
  const std::vector<Index> sorted = alone.cells.sorted.to_host();
  const std::vector<Index> begin = alone.cells.cell_begin.to_host();
  for (std::int64_t cell = 0; cell < grid.cell_count(); ++cell)
    for (Index k = begin[std::size_t(cell)]; k < begin[std::size_t(cell) + 1]; ++k) {
      const Index i = sorted[std::size_t(k)];
      ASSERT_EQ(grid.linear(grid.coord(c.position[std::size_t(i)])), cell) << "particle " << i;
      if (k > begin[std::size_t(cell)]) {
        EXPECT_LT(sorted[std::size_t(k) - 1], i) << "a cell in memory order";
      }
    }
  EXPECT_EQ(begin.back(), n);
  build_verlet_list<CpuExecCellsAlone>(alone.list, alone.cells, alone.position.data(), alone.radius.data(),
                                       alone.id.data(), n, n, skin);
  EXPECT_EQ(alone.list.begin.to_host(), with_ids.list.begin.to_host());
  EXPECT_EQ(alone.list.list.to_host(), with_ids.list.list.to_host());
}

// The GPU's two passes (ListPass: count, then fill and order), by one
// thread and by groups of lanes (host threads playing them:
// support/thread_lanes.hpp), write the CPU's list. A jittered lattice of
// two sizes and a wide skin gives each sphere up to 80 candidates in its
// cells, about eight of them neighbours: several rounds of lanes, several
// neighbours in a round.
TEST(VerletList, GpuPassesInLaneGroupsWriteTheListOfOneThread) {
  const int side = 12;
  const double pitch = 0.00105, skin = 0.0005, box = side * pitch;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.1 * pitch, 0.1 * pitch);
  Cloud c;
  for (int k = 0; k < side * side * side; ++k) {
    c.position.push_back({(k % side + 0.5) * pitch + jitter(rng), (k / side % side + 0.5) * pitch + jitter(rng),
                          (k / side / side + 0.5) * pitch + jitter(rng)});
    c.radius.push_back(float(k % 3 == 0 ? 0.0005 : 0.00045));
    c.id.push_back(ParticleId(k));
  }
  std::shuffle(c.id.begin(), c.id.end(), rng);
  const Index n = Index(c.position.size());
  BuiltList b;
  b.position.from_host(c.position);
  b.radius.from_host(c.radius);
  b.id.from_host(c.id);
  const CellGrid grid = make_cell_grid({0, 0, 0}, {box, box, box}, 0.001 + skin);
  build_cells<CpuExec>(b.cells, b.position.data(), b.id.data(), n, grid, b.scratch);
  build_verlet_list<CpuExec>(b.list, b.cells, b.position.data(), b.radius.data(), b.id.data(), n, n, skin);
  const std::vector<ListOffset> expected_begin = b.list.begin.to_host();
  const std::vector<Index> expected = b.list.list.to_host();
  ASSERT_GT(expected.size(), std::size_t(6) * std::size_t(n));  // neighbours to find: about 8 a sphere

  const CellCandidates cells{b.cells.grid, b.cells.sorted.data(), b.cells.cell_begin.data()};
  const WithinSkin near{b.position.data(), b.radius.data(), skin, grid.box};
  std::vector<ListOffset> begin(std::size_t(n) + 1, 0);
  std::vector<Index> list(expected.size(), -1);
  const ListPass<ListPassKind::count> count{cells, near, b.id.data(), begin.data(), nullptr};
  const ListPass<ListPassKind::fill> fill{cells, near, b.id.data(), begin.data(), list.data()};
  for (Index i = 0; i < n; ++i) count(i);  // one thread a sphere
  for (Index i = 0; i < n; ++i) begin[std::size_t(i) + 1] += begin[std::size_t(i)];
  ASSERT_EQ(begin, expected_begin);
  for (Index i = 0; i < n; ++i) fill(i);
  ASSERT_EQ(list, expected);

  for (int lanes : {2, 8, 32})
    for (Index i = 0; i < n; i += 7) {
      const std::size_t row = std::size_t(expected_begin[std::size_t(i)]);
      const std::size_t end = std::size_t(expected_begin[std::size_t(i) + 1]);
      std::fill(list.begin() + std::ptrdiff_t(row), list.begin() + std::ptrdiff_t(end), -1);
      const ListOffset counted = begin[std::size_t(i) + 1];
      begin[std::size_t(i) + 1] = 12345;
      test::run_lanes(lanes, [&](const test::ThreadLane& lane) { count.in_group(i, lane); });
      EXPECT_EQ(begin[std::size_t(i) + 1], ListOffset(end - row)) << lanes << " lanes, sphere " << i;
      begin[std::size_t(i) + 1] = counted;
      test::run_lanes(lanes, [&](const test::ThreadLane& lane) { fill.in_group(i, lane); });
      EXPECT_TRUE(std::equal(list.begin() + std::ptrdiff_t(row), list.begin() + std::ptrdiff_t(end),
                             expected.begin() + std::ptrdiff_t(row)))
          << lanes << " lanes, sphere " << i;
    }

  // In one pass: rows of 16 hold every sphere's neighbours (up to 14 here),
  // rows of 7 not all of them (those spheres pass over their cells again in
  // ListPlace); by one thread a sphere, then by groups of lanes for every
  // 13th sphere, the same list.
  for (int width : {16, 7}) {
    std::vector<Index> rows(std::size_t(n) * std::size_t(width), -1);
    const ListPass<ListPassKind::stage> stage{cells, near, b.id.data(), begin.data(), rows.data(), width};
    const ListPlace place{fill, rows.data(), width};
    std::fill(begin.begin(), begin.end(), 12345);
    std::fill(list.begin(), list.end(), -1);
    int beyond = 0;
    for (Index i = 0; i < n; ++i) stage(i);
    for (Index i = 0; i < n; ++i) {
      beyond += begin[std::size_t(i) + 1] > ListOffset(width);
      begin[std::size_t(i) + 1] += begin[std::size_t(i)];
    }
    ASSERT_EQ(begin, expected_begin) << "rows of " << width;
    for (Index i = 0; i < n; ++i) place(i);
    EXPECT_EQ(list, expected) << "rows of " << width;
    EXPECT_EQ(beyond > 0, width == 7) << "spheres beyond rows of " << width << ": " << beyond;
    for (int lanes : {2, 8, 32})
      for (Index i = 0; i < n; i += 13) {
        const std::size_t row = std::size_t(expected_begin[std::size_t(i)]);
        const std::size_t end = std::size_t(expected_begin[std::size_t(i) + 1]);
        begin[std::size_t(i) + 1] = 12345;
        test::run_lanes(lanes, [&](const test::ThreadLane& lane) { stage.in_group(i, lane); });
        EXPECT_EQ(begin[std::size_t(i) + 1], ListOffset(end - row)) << width << ", " << lanes << " lanes, sphere " << i;
        begin[std::size_t(i) + 1] = expected_begin[std::size_t(i) + 1];
        std::fill(list.begin() + std::ptrdiff_t(row), list.begin() + std::ptrdiff_t(end), -1);
        test::run_lanes(lanes, [&](const test::ThreadLane& lane) { place.in_group(i, lane); });
        EXPECT_TRUE(std::equal(list.begin() + std::ptrdiff_t(row), list.begin() + std::ptrdiff_t(end),
                               expected.begin() + std::ptrdiff_t(row)))
            << "rows of " << width << ", " << lanes << " lanes, sphere " << i;
      }
  }
}

// A build in one pass takes rows as wide as the room allows, up to 32, and
// only where they hold at least twice the old list's mean and one more.
TEST(VerletList, StagedRowsFitTheRoomAndTwiceTheMean) {
  const std::size_t n = 1000;
  EXPECT_EQ(staged_list_width(20 * n * 4, 6 * n, n), 20);
  EXPECT_EQ(staged_list_width(100 * n * 4, 6 * n, n), kMaxStagedWidth);
  EXPECT_EQ(staged_list_width(13 * n * 4, 6 * n, n), 13);
  EXPECT_EQ(staged_list_width(12 * n * 4, 6 * n, n), 0);  // twice the mean and one more: 13
  EXPECT_EQ(staged_list_width(100 * n * 4, 0, n), 0);     // no old list: two passes
  EXPECT_EQ(staged_list_width(0, 6 * n, n), 0);
}

// The list keeps the positions it was built on; the kick-drift's check
// (ListWatch, read one step late: tests/neighbor/test_list_lag.cpp) measures
// from them, to the nearest image.
TEST(VerletList, GoesStaleBeyondHalfTheSkin) {
  const double box = 0.006, skin = 0.0002;
  Cloud c = random_cloud(500, box, 11);
  BuiltList b;
  build(b, c, 500, skin, box);
  const std::vector<Vec3f> reference = b.list.reference.to_host();  // fp32 roundings of the positions
  ASSERT_EQ(reference.size(), std::size_t(500));
  for (std::size_t i = 0; i < reference.size(); ++i) ASSERT_EQ(norm2(reference[i] - Vec3f(c.position[i])), 0.0f) << i;
  auto check = [&](double dy) {
    ListVerdict v;
    const ListWatch watch{b.list.reference.data(), b.list.box, 0.5 * b.list.skin, 0.0, &v};
    watch(123, c.id[123], c.position[123] + Vec3d(0, dy, 0), 0.0);
    return v;
  };
  EXPECT_EQ(check(0.49 * skin).stale_now, 0);
  EXPECT_EQ(check(0.51 * skin).stale_now, 1);
  EXPECT_EQ(check(-0.51 * skin).stale_next, 1);
}

// A gas of polydisperse spheres with random velocities in a box, undamped and
// frictionless, so that a contact force is k * overlap along the normal.
SceneSpec gas_scene(double box, int n) {
  SceneSpec scene = base_scene(2500, 1000, 1.0);
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {box + 0.001, box + 0.001, box + 0.001};
  const Vec3d lo(0, 0, 0), hi(box, box, box);
  scene.walls = {plane_wall(lo, {1, 0, 0}), plane_wall(hi, {-1, 0, 0}), plane_wall(lo, {0, 1, 0}),
                 plane_wall(hi, {0, -1, 0}), plane_wall(lo, {0, 0, 1}), plane_wall(hi, {0, 0, -1})};
  scene.gravity = {0, 0, 0};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> speed(-0.5, 0.5);
  // On a lattice of pitch 2.2 mm, every fifth site large: no overlap at t = 0.
  const int side = int(std::ceil(std::cbrt(double(n))));
  const double pitch = box / side;
  for (int k = 0; k < n; ++k) {
    const Vec3d x((k % side + 0.5) * pitch, (k / side % side + 0.5) * pitch, (k / side / side + 0.5) * pitch);
    scene.particles.push_back(
        particle(ParticleId(k), k % 5 == 0 ? kLarge : kSmall, x, {speed(rng), speed(rng), speed(rng)}));
  }
  scene.time_step = 2e-6;
  return scene;
}

class VerletListRun : public testing::TestWithParam<Backend> {};

// After many list rebuilds, the forces are still those of every overlapping
// pair: a contact the list had missed (built wrong, or kept when stale) would
// show as its whole force.
TEST_P(VerletListRun, ForcesMatchBruteForceAfterManyRebuilds) {
  const double box = 0.0132;
  SceneSpec scene = gas_scene(box, 216);
  scene.verlet_skin = 0.02;  // rebuilt every few steps
  RunOptions options{GetParam()};
  Simulation sim(scene, options);
  sim.run(3000);
  const ParticleSnapshot s = sim.snapshot();
  int touching = 0, bad = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    Vec3d f;
    double scale = 0;
    for (std::size_t j = 0; j < s.size(); ++j) {
      const Vec3d d = s.position[i] - s.position[j];
      const double overlap = double(s.radius[i]) + double(s.radius[j]) - norm(d);
      if (j == i || overlap <= 0) continue;
      f += d * (1000 * overlap / norm(d));
      scale += 1000 * overlap;
    }
    for (const Wall& w : scene.walls) {
      const double overlap = double(s.radius[i]) - dot(s.position[i] - w.point, w.normal);
      if (overlap > 0) f += w.normal * (1000 * overlap), scale += 1000 * overlap;
    }
    touching += scale > 0;
    if (norm(s.force[i] - f) > 1e-5 * scale && bad++ < 10)
      ADD_FAILURE() << "particle " << s.id[i] << ": force " << norm(s.force[i]) << " N, brute force " << norm(f);
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(touching, 5);
}

TEST_P(VerletListRun, NegativeOrNonFiniteSkinIsRefused) {
  SceneSpec scene = gas_scene(0.0132, 8);
  for (double skin : {-0.01, std::nan(""), std::numeric_limits<double>::infinity()}) {
    scene.verlet_skin = skin;
    RunOptions options{GetParam()};
    try {
      Simulation sim(scene, options);
      ADD_FAILURE() << "skin " << skin << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("Verlet skin"), std::string::npos) << e.what();
    }
  }
}

// Spheres of radii 0.95-1.05 mm on a cubic lattice of pitch 2 mm in a box
// that holds it (about half the neighbour pairs overlap), ids shuffled, thrown
// at +-0.05 m/s under gravity with friction: most spheres keep several
// contacts at once, so the order of their sums shows in the bits.
SceneSpec packed_scene() {
  constexpr int kSide = 6;
  constexpr double kPitch = 0.002, kBox = kSide * kPitch;
  SceneSpec scene = base_scene(2500, 1000, 0.5, 0.5);
  scene.effects = kFriction;
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {kBox + 0.001, kBox + 0.001, kBox + 0.001};
  const Vec3d lo(0, 0, 0), hi(kBox, kBox, kBox);
  scene.walls = {plane_wall(lo, {1, 0, 0}), plane_wall(hi, {-1, 0, 0}), plane_wall(lo, {0, 1, 0}),
                 plane_wall(hi, {0, -1, 0}), plane_wall(lo, {0, 0, 1}), plane_wall(hi, {0, 0, -1})};
  scene.gravity = {0, 0, -9.81};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> radius(0.00095, 0.00105), speed(-0.05, 0.05);
  std::vector<ParticleId> ids(kSide * kSide * kSide);
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = ParticleId(k);
  std::shuffle(ids.begin(), ids.end(), rng);
  for (int k = 0; k < int(ids.size()); ++k) {
    const Vec3d x((k % kSide + 0.5) * kPitch, (k / kSide % kSide + 0.5) * kPitch, (k / kSide / kSide + 0.5) * kPitch);
    scene.particles.push_back(particle(ids[std::size_t(k)], radius(rng), x, {speed(rng), speed(rng), speed(rng)}));
  }
  scene.time_step = 2e-6;
  return scene;
}

// Each particle's contacts are summed in ascending partner id, whatever the
// list held when it was built: a frictional run is bitwise the same for any
// skin and any memory re-sorting schedule, on either backend. (A list left
// in cell order fails this: the skins make different grids.)
TEST_P(VerletListRun, ResultDoesNotDependOnTheRebuildSchedule) {
  SceneSpec scene = packed_scene();
  std::vector<ParticleSnapshot> results;
  for (const auto& [skin, reorder] : {std::pair{0.02, 25}, std::pair{0.5, 7}, std::pair{0.1, 0}}) {
    scene.verlet_skin = skin;
    RunOptions options{GetParam()};
    options.reorder_interval = reorder;
    Simulation sim(scene, options);
    sim.run(2000);
    results.push_back(sim.snapshot());
  }
  const auto same = [](const Vec3d& a, const Vec3d& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  EXPECT_GT(kinetic_energy(results[0]), 0);
  int crowded = 0;  // spheres with three contacts or more at the end (walls included)
  for (const auto c : results[0].contacts) crowded += c >= 3;
  EXPECT_GT(crowded, int(results[0].size()) / 2);
  for (std::size_t r = 1; r < results.size(); ++r)
    for (std::size_t i = 0; i < results[0].size(); ++i) {
      ASSERT_TRUE(same(results[r].position[i], results[0].position[i])) << "run " << r << ", particle " << i;
      ASSERT_TRUE(same(results[r].angular_velocity[i], results[0].angular_velocity[i]))
          << "run " << r << ", particle " << i;
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, VerletListRun, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
