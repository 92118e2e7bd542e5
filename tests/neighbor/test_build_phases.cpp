// The order of a list build's phases (engine/neighbour_finder.hpp,
// NeighbourFinder::build): the follower (the pair history) keeps its
// contacts before the cell list is sorted, while neither a cell list nor the
// staging buffer is held, not even those a re-sort left (build_cell_list
// then reorder, as Simulation::reorder_if_due does before a build), and the
// new list is built once the cell list is gone. With friction a build's
// kept contacts are the run's peak (docs/PERFORMANCE.md, "The contacts kept
// before the sort"): kept beside the cell list, they would stand 8 bytes per
// particle higher (its order and offsets), which the CPU's high-water mark
// cannot show (its peak is the merge's, where the cell list is gone either
// way), so the order itself is checked here.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "backend/cpu/cpu_exec.hpp"
#include "engine/neighbour_finder.hpp"
#include "neighbor/cell_grid.hpp"

namespace gs::test {
namespace {

constexpr double kBox = 0.01, kRadius = 0.0003, kSkin = 0.00006;

// What a follower sees of the finder when it is told of each phase.
struct Spy final : ListFollower {
  const NeighbourFinder<CpuExec>* finder = nullptr;
  const DeviceArray<unsigned char>* scratch = nullptr;
  int building = 0, built = 0;
  std::size_t cells_at_building = 0, scratch_at_building = 0, cells_at_built = 0;
  void list_replacing(const ParticleStore&) override {}
  void list_building(const ParticleStore&) override {
    ++building;
    cells_at_building += finder->cell_order().bytes();
    scratch_at_building += scratch->bytes();
  }
  void list_built(const ParticleStore&) override {
    ++built;
    cells_at_built += finder->cell_order().bytes();
  }
  std::size_t entry_bytes() const override { return 0; }
};

TEST(BuildPhases, ContactsAreKeptBeforeTheCellListAndTheSortsBuffers) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  const Index n = 4000;
  std::vector<Vec3d> x;
  std::vector<float> r;
  std::vector<ParticleId> id;
  for (Index i = 0; i < n; ++i) {
    x.push_back({kBox * u(rng), kBox * u(rng), kBox * u(rng)});
    r.push_back(float(kRadius));
    id.push_back(ParticleId(i));
  }
  ParticleStore s;
  s.place_on(Backend::cpu);
  s.n_owned = n;
  s.position.from_host(x);
  s.radius.from_host(r);
  s.id.from_host(id);
  DeviceArray<unsigned char> scratch(Backend::cpu);
  NeighbourFinder<CpuExec> finder(scratch);
  Spy spy;
  spy.finder = &finder;
  spy.scratch = &scratch;
  finder.follow(&spy);
  const CellGrid grid = make_cell_grid({0, 0, 0}, {kBox, kBox, kBox}, 2 * kRadius + kSkin);
  finder.build(s, grid, kSkin);
  // A re-sort's cell list and a gather in the staging buffer, then a build.
  finder.build_cell_list(s, grid);
  ASSERT_GT(finder.cell_order().bytes(), 0u);
  scratch.resize_discarding(std::size_t(n) * sizeof(double));
  finder.build(s, grid, kSkin);
  ASSERT_EQ(spy.building, 2);
  ASSERT_EQ(spy.built, 2);
  EXPECT_EQ(spy.cells_at_building, 0u);
  EXPECT_EQ(spy.scratch_at_building, 0u);
  EXPECT_EQ(spy.cells_at_built, 0u);  // the new springs come once the cell list is gone
  EXPECT_GT(finder.verlet().list.size(), std::size_t(n));  // a list was built: about 5 entries a sphere
}

}  // namespace
}  // namespace gs::test
