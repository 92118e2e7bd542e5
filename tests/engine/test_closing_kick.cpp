// A step's closing half kick waits inside Simulation::run for the next
// step's kick-drift, which applies it first (KickDrift::closing_kick), and
// run() finishes it before it returns. One run of N steps therefore defers
// N - 1 kicks, and N runs of one step defer none: the two must end in the
// same bits, velocities, spins, positions, forces and springs alike, where
// the state is rounded to fp32 after every kick too, where an inlet inserts
// particles between two steps (insertion finishes the kick first), and where
// a fault stops the run (the kick is finished before the fault is thrown).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "scene/scene_time_step.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// Eight frictional spheres thrown spinning into a box corner under gravity:
// they hit the walls and each other within the run.
SceneSpec thrown(Precision precision) {
  SceneSpec s = base_scene(2500, 2000, 0.6, 0.5);
  s.effects = kFriction;
  s.precision = precision;
  s.gravity = {0, 0, -9.81};
  s.walls = {plane_wall({0, 0, -0.005}, {0, 0, 1}), plane_wall({-0.005, 0, 0}, {1, 0, 0}),
             plane_wall({0, -0.005, 0}, {0, 1, 0})};
  ParticleId id = 0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        ParticleInit p = particle(id, 0.001, {-0.0035 + 0.0021 * i, -0.0035 + 0.0021 * j, -0.0035 + 0.0021 * k},
                                  {-0.2 + 0.05 * id, -0.1 * j, -0.3});
        p.angular_velocity = {10.0 * i, -20.0 + id, 5.0 * k};
        s.particles.push_back(p);
        ++id;
      }
  s.contact_time = critical_contact_time(s);
  s.time_step = 0.02 * s.contact_time;
  return s;
}

// The box of thrown() fed from above by an inlet every 20 steps.
SceneSpec fed() {
  SceneSpec s = thrown(Precision::fp32);
  InletSpec in;
  in.name = "feed";
  in.region.min = {-0.005, -0.005, 0.0};
  in.region.max = {0.003, 0.003, 0.015};
  in.size.kind = SizeSpec::Kind::uniform;
  in.size.radius_min = 0.0005;
  in.size.radius_max = 0.0007;
  in.rate = 1e5;  // per second: about ten spheres per batch
  in.interval_steps = 20;
  in.tmpl.velocity = {0, 0, -0.2};
  in.seed = 5;
  s.inlets.push_back(in);
  return s;
}

void expect_same_state(Simulation& a, Simulation& b) {
  const ParticleSnapshot sa = a.snapshot(), sb = b.snapshot();
  ASSERT_EQ(sa.size(), sb.size());
  EXPECT_TRUE(same_bits(sa.position, sb.position));
  EXPECT_TRUE(same_bits(sa.velocity, sb.velocity));
  EXPECT_TRUE(same_bits(sa.angular_velocity, sb.angular_velocity));
  EXPECT_TRUE(same_bits(sa.force, sb.force));
  EXPECT_TRUE(same_bits(sa.torque, sb.torque));
  const HostHistory ha = a.history(), hb = b.history();
  EXPECT_TRUE(same_bits(ha.partner, hb.partner));
  EXPECT_TRUE(same_bits(ha.tangential, hb.tangential));
}

class ClosingKick : public testing::TestWithParam<Backend> {};

TEST_P(ClosingKick, OneLongRunEqualsOneStepRuns) {
  for (Precision precision : {Precision::fp32, Precision::fp64, Precision::fp32_full}) {
    SCOPED_TRACE(precision_name(precision));
    const SceneSpec s = thrown(precision);
    Simulation once(s, {GetParam()}), stepwise(s, {GetParam()});
    const int steps = 1500;
    once.run(steps);
    for (int k = 0; k < steps; ++k) stepwise.run(1);
    // Every sphere met a wall or another: none flies freely any more.
    const ParticleSnapshot moved = once.snapshot();
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const Vec3d free_flight = s.particles[moved.id[i]].velocity + s.gravity * once.time();
      EXPECT_GT(norm(moved.velocity[i] - free_flight), 0.01) << "sphere " << moved.id[i];
    }
    expect_same_state(once, stepwise);
  }
}

// A batch inserted after a step's forces has had no kick yet: where the
// step's closing kick were left to the next kick-drift, it would get one
// (and the run's end would give it one).
TEST_P(ClosingKick, InsertionBetweenStepsSeesWholeSteps) {
  const SceneSpec s = fed();
  Simulation once(s, {GetParam()}), stepwise(s, {GetParam()});
  const int steps = 100;  // a batch every 20 steps: one at the last
  once.run(steps - 20);
  const ParticleId before_last_batch = ParticleId(once.particle_count());
  once.run(20);
  for (int k = 0; k < steps; ++k) stepwise.run(1);
  EXPECT_GT(once.particle_count(), Index(before_last_batch) + 2) << "the inlet inserted spheres at the last step";
  const ParticleSnapshot sa = once.snapshot();
  for (std::size_t i = 0; i < sa.size(); ++i)
    if (sa.id[i] >= before_last_batch) {
      EXPECT_EQ(sa.velocity[i].x, s.inlets[0].tmpl.velocity.x) << "sphere " << sa.id[i];
      EXPECT_EQ(sa.velocity[i].z, s.inlets[0].tmpl.velocity.z) << "sphere " << sa.id[i];
    }
  expect_same_state(once, stepwise);
}

// A fault found inside run() (a sphere left the domain) leaves the state at
// a whole step, as the driver writes it to the fault snapshot: the same as
// where the run of that one step found it.
TEST_P(ClosingKick, AFaultLeavesAWholeStep) {
  SceneSpec s = thrown(Precision::fp32);
  s.particles.push_back(particle(8, 0.001, {0.0185, 0.015, 0.015}, {2, 0, 0}));
  RunOptions in_loop{GetParam()}, at_end{GetParam()};
  in_loop.fault_check_interval = 1;  // read after every step inside run()
  at_end.fault_check_interval = 0;   // read only as run() ends
  Simulation once(s, in_loop), stepwise(s, at_end);
  EXPECT_THROW(once.run(5000), SimulationFault);
  long long steps = 0;
  try {
    for (; steps < 5000; ++steps) stepwise.run(1);
  } catch (const SimulationFault&) {
  }
  EXPECT_GT(steps, 10);
  EXPECT_LT(steps, 5000);
  EXPECT_EQ(once.step_count(), stepwise.step_count());
  expect_same_state(once, stepwise);
}

INSTANTIATE_TEST_SUITE_P(Backends, ClosingKick, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
