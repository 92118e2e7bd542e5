// Stability case 8 (docs/STABILITY.md): a run that goes unstable is stopped,
// not silently blown up. The scene is built in code with a time step ten
// times the accepted limit (2 t_c; the loader would refuse it): velocity
// Verlet on a contact is unstable above omega dt = 2, i.e. dt > 0.64 t_c, so
// the overlaps of a bed resting on its contacts grow by a factor each step
// until a sphere jumps more than half a cell, leaves the domain, turns
// non-finite or outruns a Verlet list kept for its step. Simulation::run must
// throw SimulationFault naming the step, the particle and the cause, within
// fault_check_interval steps of the fault.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "contact/contact_time.hpp"
#include "core/fault.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;

// A simple cubic stack of touching spheres on the floor of a box: every
// sphere rests on contacts from the first step.
SceneSpec stack(int per_side, int layers) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
  scene.effects = kFriction;
  scene.precision = Precision::fp32;
  scene.gravity = {0, 0, -kGravity};
  const double width = per_side * 2 * kRadius, height = 2 * layers * 2 * kRadius;
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {width + 0.001, width + 0.001, height + 0.001};
  scene.walls = box_walls({0, 0, 0}, {width, width, height});
  ParticleId id = 0;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < per_side; ++j)
      for (int i = 0; i < per_side; ++i)
        scene.particles.push_back(particle(id++, kRadius, {(2 * i + 1) * kRadius, (2 * j + 1) * kRadius,
                                                           (2 * k + 1) * kRadius}));
  set_largest_accepted_step(scene);
  scene.time_step *= 10;  // far above the limit
  return scene;
}

class StabilityUnstableRunTest : public testing::TestWithParam<Backend> {};

TEST_P(StabilityUnstableRunTest, RunThrowsSimulationFaultNamingStepParticleAndCause) {
  const SceneSpec scene = stack(short_or_long(5, 40), short_or_long(8, 40));
  const std::regex format("step ([0-9]+): particle ([0-9]+): (.+)");
  for (const int check_interval : {50, 1}) {
    SCOPED_TRACE("fault_check_interval " + std::to_string(check_interval));
    RunOptions options{GetParam()};
    options.fault_check_interval = check_interval;
    Simulation sim(scene, options);
    std::string message;
    try {
      sim.run(100000);
    } catch (const SimulationFault& fault) {
      message = fault.what();
    }
    ASSERT_FALSE(message.empty()) << "the run went " << sim.step_count() << " steps at 2 t_c without a fault";
    std::smatch m;
    ASSERT_TRUE(std::regex_match(message, m, format)) << message;
    const long long step = std::stoll(m[1]);
    const long long id = std::stoll(m[2]);
    const std::string cause = m[3];
    std::printf("[ measured ] check interval %d: \"%s\", thrown at step %lld\n", check_interval, message.c_str(),
                sim.step_count());
    EXPECT_GT(step, 0);
    EXPECT_LE(step, sim.step_count());
    EXPECT_LT(sim.step_count() - step, check_interval);  // caught at the first check after it
    EXPECT_GE(id, 0);
    EXPECT_LT(id, (long long)scene.particles.size());
    EXPECT_TRUE(cause == fault_cause(kFaultLeftDomain) || cause == fault_cause(kFaultTooFast) ||
                cause == fault_cause(kFaultNotFinite) || cause == fault_cause(kFaultListOutrun))
        << cause;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityUnstableRunTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
