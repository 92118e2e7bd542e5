// The Verlet list's staleness read one step late (neighbor/verlet_list.hpp,
// ListWatch): the verdict of step n decides the rebuild at step n + 1 (with
// ranks, of the halo too), so the list is rebuilt when a particle's distance from where the
// list saw it, plus its last move, plus the margin delta (a tenth of the
// skin) exceeds half the skin; and where a list so kept turns out, a step
// later, not to have covered its step (a particle more than half the skin
// from where the list saw it), the run stops with a fault naming the
// particle and step. Checked on the check itself, on the skin it holds the
// moves to, on the steps a run rebuilds at (computed here from the rule, for
// spheres in free flight), and on a sphere at rest struck by a wall hard
// enough to move it 1.5 skins in one step (fault), or gently (none).
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "backend/cpu/cpu_exec.hpp"
#include "core/fault.hpp"
#include "core/periodic_box.hpp"
#include "engine/neighbour_finder.hpp"
#include "neighbor/cell_grid.hpp"
#include "neighbor/verlet_list.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.001;

// The check of one particle (id 9) at distance d (in skins) from its
// reference, having moved m skins this step.
ListVerdict verdict_at(double d, double m) {
  const double skin = 0.0002;
  const Vec3f reference(0.001f, 0.002f, 0.003f);  // its rounding (7e-10 m) is far below the steps tested
  ListVerdict v;
  const ListWatch watch{&reference, PeriodicBox{}, 0.5 * skin, kListMarginOfSkin * skin, &v};
  watch(0, 9, Vec3d(reference) + Vec3d(0, d * skin, 0), m * skin);
  return v;
}

TEST(ListLag, VerdictCountsTheLastMoveAndTheMargin) {
  ASSERT_DOUBLE_EQ(kListMarginOfSkin, 0.1);
  // D + m + delta against half the skin: stale for the next step.
  EXPECT_EQ(verdict_at(0.39, 0.0).stale_next, 0);
  EXPECT_EQ(verdict_at(0.41, 0.0).stale_next, 1);
  EXPECT_EQ(verdict_at(0.29, 0.1).stale_next, 0);
  EXPECT_EQ(verdict_at(0.31, 0.1).stale_next, 1);
  // m + delta alone: a list built now would be stale after the next step.
  EXPECT_EQ(verdict_at(0.45, 0.39).fast, 0);
  EXPECT_EQ(verdict_at(0.0, 0.41).fast, 1);
  // D alone: stale now, naming the particle.
  EXPECT_EQ(verdict_at(0.49, 0.0).stale_now, 0);
  const ListVerdict v = verdict_at(0.51, 0.0);
  EXPECT_EQ(v.stale_now, 1);
  EXPECT_EQ(v.stale_now_particle, ParticleId(9));
}

// With ranks a rank's kick-drift watches its moves against half of the
// halo's skin where the coarse cells cut that below the list's
// (Simulation's constructor, NeighbourSearch::watch_moves), since its verdict
// is also the halo's: the watch holds the moves to half of the narrower skin,
// with the list's margin; a wider skin leaves the list's; none, no watch (and
// every step stale).
TEST(ListLag, WatchHoldsTheMovesToHalfTheNarrowerSkin) {
  ParticleStore s;
  s.place_on(Backend::cpu);
  s.n_owned = 2;
  s.position.from_host({{0, 0, 0}, {0.003, 0, 0}});
  s.radius.from_host({float(kRadius), float(kRadius)});
  s.id.from_host({0, 1});
  DeviceArray<unsigned char> scratch{Backend::cpu};
  NeighbourFinder<CpuExec> finder{scratch};
  const double skin = 0.0002;
  finder.build(s, make_cell_grid({-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}, 2 * kRadius + skin), skin);
  finder.watch_moves(0.5 * skin);
  const ListWatch narrow = finder.watch(s, 1);
  ASSERT_TRUE(narrow.active());
  EXPECT_NE(narrow.reference, nullptr);
  EXPECT_EQ(narrow.half_skin, 0.25 * skin);
  EXPECT_EQ(narrow.margin, kListMarginOfSkin * skin);
  finder.watch_moves(3 * skin);
  EXPECT_EQ(finder.watch(s, 2).half_skin, 0.5 * skin);
  finder.watch_moves(0);
  EXPECT_FALSE(finder.watch(s, 3).active());
  EXPECT_TRUE(finder.stale(s));
}

// A particle that crossed a periodic face has moved by the separation from
// its reference's nearest image (with ranks the halo counts on it too): in a
// box of 10 mm that wraps in x, 9.95 mm -> 0.04 mm is a move of 0.09 mm, not
// 9.91, and 9.95 -> 0.06 mm one of 0.11, beyond half the skin (0.1 mm).
TEST(ListLag, VerdictMeasuresAMoveAcrossAPeriodicFaceToTheNearestImage) {
  const double skin = 0.0002;
  const PeriodicBox box = make_periodic_box(1u, {0, 0, 0}, {0.01, 0.01, 0.01});
  const Vec3f reference(0.00995f, 0.005f, 0.005f);
  auto stale_now = [&](double x) {
    ListVerdict v;
    const ListWatch watch{&reference, box, 0.5 * skin, kListMarginOfSkin * skin, &v};
    watch(0, 9, Vec3d(x, 0.005, 0.005), 0);
    return v.stale_now;
  };
  EXPECT_EQ(stale_now(0.00004), 0);
  EXPECT_EQ(stale_now(0.00006), 1);
  EXPECT_EQ(stale_now(0.00995 - 0.00011), 1);  // the same move within the box
}

class ListLagRun : public testing::TestWithParam<Backend> {};

// One sphere in free flight (no gravity, nothing to touch) at a speed of
// skin / 37 per step. After a build at step k, the verdict of step n has
// D = (n - k) m with m = skin / 37: stale where (n - k) m + m + skin / 10 >
// skin / 2, i.e. n - k >= 14 (13.8), and the rebuild follows at step n + 1:
// every 15 steps. Half the skin without margin and lag would give every 19.
TEST_P(ListLagRun, RebuildsWhereTheLaggedRuleSays) {
  SceneSpec scene = base_scene(2500, 1000, 0.5);
  scene.gravity = {0, 0, 0};
  scene.time_step = 1e-5;
  RunOptions options{GetParam()};
  const double skin = scene.verlet_skin * 2 * kRadius;
  const double speed = skin / 37 / scene.time_step;
  scene.particles.push_back(particle(0, kRadius, {-0.015, 0, 0}, {speed, 0, 0}));
  Simulation sim(scene, options);
  long long expected = 0;
  for (long long step = 1; step <= 100; ++step) {
    sim.run(1);
    if (step % 15 == 0) ++expected;
    ASSERT_EQ(sim.neighbour_builds(), expected) << "after step " << step;
  }
}

// A sphere moving 0.45 skins a step: m + delta exceeds half the skin, so even
// a list built on the positions of a step may not cover the next: rebuilt
// at every step (the verdict `fast`), from the first that has one before it.
TEST_P(ListLagRun, FastSphereRebuildsEveryStep) {
  SceneSpec scene = base_scene(2500, 1000, 0.5);
  scene.gravity = {0, 0, 0};
  scene.time_step = 1e-5;
  RunOptions options{GetParam()};
  const double skin = scene.verlet_skin * 2 * kRadius;
  scene.particles.push_back(particle(0, kRadius, {-0.015, 0, 0}, {0.45 * skin / scene.time_step, 0, 0}));
  Simulation sim(scene, options);
  sim.run(1);
  EXPECT_EQ(sim.neighbour_builds(), 0);  // 0.45 skins from where the list saw it: still within half
  sim.run(20);
  EXPECT_EQ(sim.neighbour_builds(), 20);
}

// A sphere (id 7, mass m) at rest, no gravity, and a floor rising at 0.5 m/s
// that first overlaps it, by half its move of a step (25 um), after the
// drift of step 11. The sphere's verdicts say "keep" throughout (it has not
// moved); the forces of step 11 give it |a| dt^2 = k * 25 um * dt^2 / m,
// which at k = 12500 N/m and dt = 0.1 ms is 0.30 mm: 1.5 skins in step 12,
// the list kept for it. Read at step 13 (or by the fault check at the end
// of a run that stops at step 12), the run stops at its next fault check
// naming step 12 and the sphere. At k = 100 N/m (2.4 um, an eighth of
// the margin) it runs on.
SceneSpec struck_sphere(double stiffness) {
  SceneSpec scene = base_scene(2500, stiffness, 0.5);
  scene.gravity = {0, 0, 0};
  scene.time_step = 1e-4;
  const double speed = 0.5, move = speed * scene.time_step;
  Wall floor = plane_wall({0, 0, 0.004 - 10.5 * move}, {0, 0, 1});
  floor.velocity = {0, 0, speed};
  scene.walls = {floor};
  scene.particles.push_back(particle(7, kRadius, {0, 0, 0.005}));
  scene.particles.push_back(particle(3, kRadius, {0.01, 0.01, 0.01}));  // at rest, far from both
  return scene;
}

TEST_P(ListLagRun, ListOutrunInAKeptStepIsAFault) {
  const SceneSpec scene = struck_sphere(12500);
  const double mass = 2500 * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  const double jolt = 12500 * 25e-6 / mass * scene.time_step * scene.time_step;
  const double skin = scene.verlet_skin * 2 * kRadius;
  ASSERT_GT(jolt, 1.4 * skin);
  ASSERT_LT(jolt, 0.5 * kRadius);  // far less than half a cell: no other fault
  // Stopped at step 20, or at step 12 itself: the last step's verdict is
  // read by the fault check at the end of the run.
  for (const long long steps : {20, 12}) {
    Simulation sim(scene, RunOptions{GetParam()});
    std::string message;
    try {
      sim.run(steps);
    } catch (const SimulationFault& fault) {
      message = fault.what();
    }
    EXPECT_EQ(message, std::string("step 12: particle 7: ") + fault_cause(kFaultListOutrun)) << steps << " steps";
  }
}

TEST_P(ListLagRun, GentleStrikeRunsOn) {
  Simulation sim(struck_sphere(100), RunOptions{GetParam()});
  EXPECT_NO_THROW(sim.run(40));
  EXPECT_GT(sim.snapshot().velocity[1].z, 0.5) << "the floor did not strike the sphere";
}

INSTANTIATE_TEST_SUITE_P(Backends, ListLagRun, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
