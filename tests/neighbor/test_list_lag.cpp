// The Verlet list's staleness read one step late (neighbor/verlet_list.hpp,
// ListWatch): on one rank the verdict of step n decides the rebuild at step
// n + 1, so the list is rebuilt when a particle's distance from where the
// list saw it, plus its last move, plus the margin delta (a tenth of the
// skin) exceeds half the skin; and the kick-drift stops the run with a fault
// where a step's acceleration could have carried a particle past the margin
// (|a| dt^2 above nine tenths of delta). Checked on the check itself, on the
// steps a run rebuilds at (computed here from the rule, for a sphere in free
// flight) and on a sphere pressed into a wall at a step far above the stable
// limit (fault) and at one below it (none).
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "core/fault.hpp"
#include "neighbor/verlet_list.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.001;

// The check of one particle at distance d (in skins) from its reference,
// having moved m skins this step.
ListVerdict verdict_at(double d, double m) {
  const double skin = 0.0002;
  const Vec3d reference(0.001, 0.002, 0.003);
  ListVerdict v;
  const ListWatch watch{&reference, PeriodicBox{}, 0.5 * skin, kListMarginOfSkin * skin, &v};
  watch(0, reference + Vec3d(0, d * skin, 0), m * skin);
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
  // D alone: stale now (the first step of a run, which has no earlier verdict).
  EXPECT_EQ(verdict_at(0.49, 0.0).stale_now, 0);
  EXPECT_EQ(verdict_at(0.51, 0.0).stale_now, 1);
}

TEST(ListLag, GuardAllowsNineTenthsOfTheMargin) {
  const double skin = 0.0002;
  const ListWatch watch{nullptr, PeriodicBox{}, 0.5 * skin, kListMarginOfSkin * skin, nullptr};
  EXPECT_FALSE(watch.too_sudden(0.089 * skin));
  EXPECT_TRUE(watch.too_sudden(0.091 * skin));
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
  const double skin = options.verlet_skin * 2 * kRadius;
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
  const double skin = options.verlet_skin * 2 * kRadius;
  scene.particles.push_back(particle(0, kRadius, {-0.015, 0, 0}, {0.45 * skin / scene.time_step, 0, 0}));
  Simulation sim(scene, options);
  sim.run(1);
  EXPECT_EQ(sim.neighbour_builds(), 0);  // 0.45 skins from where the list saw it: still within half
  sim.run(20);
  EXPECT_EQ(sim.neighbour_builds(), 20);
}

// A sphere of mass m pressed 0.1 mm into a floor of stiffness k = 1000 N/m
// starts with |a| = k * 0.1 mm / m - g. At dt = 72 us, |a| dt^2 = 5e-5 m,
// 2.5 margins (0.02 mm at a skin of 0.1 diameters) and far below half a cell
// (1.1 mm): the first kick-drift stops the run on the margin's guard, naming
// the sphere and step 1 (omega dt = 0.7 here: twice the stable limit). At
// dt = 10 us (|a| dt^2 = 1e-6 m) the same sphere runs on.
SceneSpec pressed_sphere(double dt) {
  SceneSpec scene = base_scene(2500, 1000, 0.5);
  scene.gravity = {0, 0, -9.81};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  scene.particles.push_back(particle(7, kRadius, {0, 0, kRadius - 1e-4}));
  scene.particles.push_back(particle(3, kRadius, {0.01, 0.01, 0.005}));  // in flight, far from both
  scene.time_step = dt;
  return scene;
}

TEST_P(ListLagRun, StepBeyondTheMarginIsAFault) {
  const SceneSpec scene = pressed_sphere(7.2e-5);
  const double mass = 2500 * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  const double jolt = (1000 * 1e-4 / mass - 9.81) * scene.time_step * scene.time_step;
  const double margin = kListMarginOfSkin * RunOptions{}.verlet_skin * 2 * kRadius;
  ASSERT_GT(jolt, 2 * margin);
  ASSERT_LT(jolt, 0.5 * kRadius);
  RunOptions options{GetParam()};
  Simulation sim(scene, options);
  std::string message;
  try {
    sim.run(100);
  } catch (const SimulationFault& fault) {
    message = fault.what();
  }
  EXPECT_EQ(message, std::string("step 1: particle 7: ") + fault_cause(kFaultListMargin));
}

TEST_P(ListLagRun, StableStepRunsOn) {
  RunOptions options{GetParam()};
  Simulation sim(pressed_sphere(1e-5), options);
  EXPECT_NO_THROW(sim.run(200));
}

INSTANTIATE_TEST_SUITE_P(Backends, ListLagRun, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
