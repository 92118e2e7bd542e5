// When ranks rebuild their halo, run under mpiexec with 2, 3 or 4 ranks. A
// rank keeps its ghosts (and its Verlet list) until the kick-drift's verdict
// on some rank says a particle may have moved half the skin, and between
// rebuilds only forwards the ghosts' positions and velocities: so the ranks
// must rebuild at the steps one rank rebuilds its list at, and still compute
// the one-rank run's bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "comm/device_link.hpp"
#include "comm/scene_split.hpp"
#include "decomposition/coarse_grid.hpp"
#include "comm/snapshot_gather.hpp"
#include "scene/generators.hpp"
#include "scene/particle_sources.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

Transport& world() {
  static std::unique_ptr<Transport> t = make_mpi_transport();
  return *t;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Frictional spheres (1:2 in radius) falling onto the floor of a box cut
// into slabs along z: they cross slab boundaries and pile up.
SceneSpec falling_bed() {
  SceneSpec s = base_scene(2500, 2000, 0.5, 0.5);
  s.precision = Precision::fp32;
  s.effects = kFriction;
  s.gravity = {0, 0, -9.81};
  s.domain_min = {-0.001, -0.001, -0.001};
  s.domain_max = {0.021, 0.021, 0.041};
  s.walls = {plane_wall({0, 0, 0}, {1, 0, 0}), plane_wall({0.02, 0, 0}, {-1, 0, 0}),
             plane_wall({0, 0, 0}, {0, 1, 0}), plane_wall({0, 0.02, 0}, {0, -1, 0}), plane_wall({0, 0, 0}, {0, 0, 1})};
  RandomFillSpec fill;
  fill.region.min = {0.0015, 0.0015, 0.0015};
  fill.region.max = {0.0185, 0.0185, 0.0385};
  fill.count = 400;
  fill.size.kind = SizeSpec::Kind::uniform;
  fill.size.radius_min = 0.0006;
  fill.size.radius_max = 0.0012;
  fill.seed = 11;
  generate_random_fill(fill, s.particles);
  s.decomposition.axis = 2;
  s.time_step = 2e-5;
  return s;
}

void expect_same_state(const ParticleSnapshot& all, const ParticleSnapshot& ref) {
  ASSERT_EQ(all.size(), ref.size()) << "particles lost or duplicated";
  EXPECT_TRUE(same_bits(all.id, ref.id));
  EXPECT_TRUE(same_bits(all.position, ref.position));
  EXPECT_TRUE(same_bits(all.velocity, ref.velocity));
  EXPECT_TRUE(same_bits(all.angular_velocity, ref.angular_velocity));
  EXPECT_TRUE(same_bits(all.force, ref.force));
}

// The ranks rebuild the halo (and with it their lists) at the steps where
// one rank rebuilds its list: where the verdict of the last step's kick-drift
// says some particle may have moved half the skin by the end of this one (a
// margin ahead of half the skin, the verdict read a step late:
// neighbor/verlet_list.hpp), the vote taking every rank's particles as one
// rank takes all of them. So not every step (the whole point), and never
// later than a particle has moved half the skin since the last rebuild
// (contacts would be missed): at least as often as the exact rule, counted
// here from the one-rank run's positions after each step (the same bits as
// the ranks').
TEST(HaloSchedule, RanksRebuildWhenAParticleMayHaveMovedHalfTheSkin) {
  const SceneSpec s = falling_bed();
  RunOptions o;
  o.rebalance_interval = 0;  // a load-balance check would rebuild as well
  const long long steps = 1500;
  const double skin = s.verlet_skin * 2 * largest_radius(s);
  Simulation one(s, o);
  std::vector<Vec3d> reference = one.snapshot().position;
  long long expected = 0;
  for (long long step = 1; step <= steps; ++step) {
    one.run(1);
    const std::vector<Vec3d> x = one.snapshot().position;
    bool moved = false;
    for (std::size_t i = 0; i < x.size(); ++i) moved = moved || norm2(x[i] - reference[i]) > 0.25 * skin * skin;
    if (!moved) continue;
    ++expected;
    reference = x;
  }
  const auto exchange = split_scene(s, world());
  ASSERT_EQ(exchange->set_skin(skin), skin) << "the coarse cells cut the skin";
  Simulation many(s, o, exchange);
  many.run(steps);
  const ExchangeSplit x = exchange->split();
  const ParticleSnapshot all = gather_snapshot(world(), many.snapshot());
  if (world().rank() != 0) return;
  EXPECT_GT(expected, 10) << "the bed hardly moved: the test sees no rebuild";
  const long long builds = one.neighbour_builds();
  EXPECT_GE(builds, expected) << "one rank kept its list past half the skin";
  EXPECT_LT(builds, steps / 5) << "rebuilt at most steps";
  EXPECT_EQ(many.neighbour_builds(), builds) << "the ranks rebuilt where one rank did not, or not where it did";
  EXPECT_EQ(x.rebuilds, builds + 1) << "the halo is built once at the start, then at every rebuild";
  EXPECT_EQ(x.forwards, steps - builds);
  std::printf("[ measured ] list builds in %lld steps: %lld (ranks and one rank); the exact rule %lld\n", steps,
              builds, expected);
  expect_same_state(all, one.snapshot());
}

// A sphere touched by 135 small ones: a CPU rank walks its Verlet list, kept
// in id order, so it sums all of them as one rank does (the search of the
// touching partners in the cells, which ranks used before, held 128).
TEST(HaloSchedule, SphereTouchedByMoreThan128OnCpuRanks) {
  SceneSpec s = base_scene(2500, 2000, 0.5);
  s.domain_min = {0, 0, 0};
  s.domain_max = {0.02, 0.02, 0.04};  // tall enough for 4 slabs
  const Vec3d centre{0.01, 0.01, 0.01};
  const double big = 0.003, small = 0.00045, shell = big + small - 1e-5;
  ParticleInit p;
  p.radius = big;
  p.position = centre;
  s.particles.push_back(p);
  const int n = 135;  // on a Fibonacci sphere: neighbours 1.1 mm apart, more than a small diameter
  for (int k = 0; k < n; ++k) {
    const double z = 1 - (2 * k + 1.0) / n, r = std::sqrt(1 - z * z), phi = 2.399963229728653 * k;
    p.radius = small;
    p.position = centre + Vec3d{r * std::cos(phi), r * std::sin(phi), z} * shell;
    s.particles.push_back(p);
  }
  for (std::size_t i = 0; i < s.particles.size(); ++i) s.particles[i].id = ParticleId(i);
  s.decomposition.axis = 2;
  s.time_step = 1e-6;
  Simulation one(s, RunOptions{});
  one.run(5);
  Simulation many(s, RunOptions{}, split_scene(s, world()));
  many.run(5);
  const ParticleSnapshot all = gather_snapshot(world(), many.snapshot());
  if (world().rank() != 0) return;
  const ParticleSnapshot ref = one.snapshot();
  EXPECT_GT(norm2(ref.force[0]), 0.0) << "the big sphere feels nothing";
  expect_same_state(all, ref);
}

// Pairs of spheres that meet head-on across every face of the coarse cells
// along z (so across every slab boundary, whatever the cuts): the upper one
// starts a tenth of the skin above the face, the lower one its diameter plus
// half the skin below, so they touch after each has moved 0.3 skins, before
// the halo is rebuilt. The rank above sees the lower sphere only because
// ghosts reach the diameter plus the skin: with the diameter alone it would
// miss the contact until the next rebuild.
void expect_contacts_across_boundaries(const RunOptions& o) {
  SceneSpec s = base_scene(2500, 2000, 0.5, 0.5);
  s.effects = kFriction;
  s.domain_min = {0, 0, 0};
  s.domain_max = {0.08, 0.01, 0.04};
  s.decomposition.axis = 2;
  s.time_step = 1e-5;
  const double r = 0.001, d = 2 * r, skin = s.verlet_skin * d, v = 0.1;
  const CoarseGrid g = CoarseGrid::make(s.domain_min, s.domain_max, d * (1 + s.verlet_skin));
  for (int k = 2; k < g.dims[2]; ++k) {
    const double face = g.face(2, k), x = 0.002 + 0.004 * (k - 2);
    s.particles.push_back(particle(ParticleId(s.particles.size()), r, {x, 0.005, face + 0.1 * skin}, {0, 0, -v}));
    s.particles.push_back(particle(ParticleId(s.particles.size()), r, {x, 0.005, face - d - 0.5 * skin}, {0, 0, v}));
  }
  Simulation one(s, o);
  const auto exchange = split_scene(s, world());
  if (o.backend == Backend::cuda) exchange->use_device_link(make_nccl_link(world()));
  Simulation many(s, o, exchange);
  const long long steps = 72;  // in contact from step 61 (0.3 skins at 1 um per step) for about 23 steps
  one.run(steps);
  many.run(steps);
  const ParticleSnapshot all = gather_snapshot(world(), many.snapshot());
  if (world().rank() != 0) return;
  const ParticleSnapshot ref = one.snapshot();
  EXPECT_EQ(exchange->split().rebuilds, 1) << "the halo was rebuilt before the contacts";
  EXPECT_GT(norm2(ref.force[0]), 0.0) << "the pairs have not met";
  expect_same_state(all, ref);
}

TEST(HaloSchedule, ContactFormedAcrossASlabBoundaryBetweenRebuilds) { expect_contacts_across_boundaries(RunOptions{}); }

// The same on GPU ranks, each on a GPU of its own, over NCCL, against one
// GPU (GS_TEST_BACKENDS naming cuda; skipped otherwise): the GPU keeps no
// Verlet list, but its halo follows the same schedule.
TEST(HaloSchedule, ContactFormedAcrossASlabBoundaryOnGpus) {
  const std::vector<Backend> b = test_backends();
  const bool wanted = std::find(b.begin(), b.end(), Backend::cuda) != b.end() && nccl_available();
  const bool own_gpu = wanted && cuda_device_available() && select_cuda_device(world().local_rank());
  if (world().min(own_gpu ? 1 : 0) == 0) GTEST_SKIP() << "needs GS_TEST_BACKENDS with cuda, NCCL, and a GPU per rank";
  RunOptions o;
  o.backend = Backend::cuda;
  expect_contacts_across_boundaries(o);
}

}  // namespace
}  // namespace gs::test
