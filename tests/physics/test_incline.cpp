// A sphere on an incline of angle theta (gravity tilted by theta, the plane
// kept horizontal) with Coulomb friction mu. The rigid-body solution:
//   tan(theta) < 7/2 mu: it rolls without slipping, a = 5/7 g sin(theta),
//                         omega R = v;
//   otherwise:           it slides, a = g (sin(theta) - mu cos(theta)), and
//                         the friction torque spins it up at
//                         alpha = 5 mu g cos(theta) / (2 R).
// Tolerance 0.5%: the rigid-body solution neglects the overlap (delta / R ~ 1e-4
// shortens the lever arm) and the engine keeps mass and inertia in fp32; the
// measured deviation is ~1e-4.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;
constexpr double kMu = 0.2;  // rolling below tan(theta) = 0.7, i.e. theta < 35 degrees

struct Motion {
  double acceleration;          // along the slope, from v(t2) - v(t1)
  double angular_acceleration;  // about the axis that rolling down the slope turns
  double rolling_mismatch;      // |omega R - v| / v at t2
};

// Measures between t1 = 0.01 s and t2 = 0.05 s: the tangential spring loads
// and its oscillation decays (zeta = 0.22, period 0.6 ms) well before t1.
Motion slide_down(Backend backend, double theta) {
  const double mass = stored_sphere_mass(kRadius, kDensity);
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, kMu);
  scene.effects = kFriction;
  scene.domain_min = {-0.004, -0.004, -0.004};
  scene.domain_max = {0.02, 0.004, 0.004};
  scene.gravity = {kGravity * std::sin(theta), 0, -kGravity * std::cos(theta)};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  // Start at rest at the static overlap, so that the normal direction has no transient.
  const double overlap = mass * kGravity * std::cos(theta) / kStiffness;
  scene.particles = {particle(0, kRadius, {0, 0, kRadius - overlap})};
  scene.time_step = linear_contact_time(kStiffness, mass, kRestitution) / 50;

  Simulation sim(scene, {backend});
  const double t1 = 0.01, t2 = 0.05;
  sim.run(std::llround(t1 / scene.time_step));
  const ParticleSnapshot s1 = sim.snapshot();
  sim.run(std::llround(t2 / scene.time_step) - sim.step_count());
  const ParticleSnapshot s2 = sim.snapshot();
  const double dt = s2.time - s1.time;
  // Rolling in +x on a plane with normal +z turns the sphere about +y.
  const double v = s2.velocity[0].x, omega = s2.angular_velocity[0].y;
  return {(v - s1.velocity[0].x) / dt, (omega - s1.angular_velocity[0].y) / dt, std::fabs(omega * kRadius - v) / v};
}

class InclineTest : public testing::TestWithParam<Backend> {};

TEST_P(InclineTest, RollsWithoutSlippingBelowCriticalAngle) {
  const double theta = 20 * M_PI / 180;  // tan = 0.36 < 7/2 mu = 0.7
  ASSERT_LT(std::tan(theta), 3.5 * kMu);
  const Motion m = slide_down(GetParam(), theta);
  EXPECT_NEAR(m.acceleration / (5.0 / 7.0 * kGravity * std::sin(theta)), 1.0, 0.005);
  EXPECT_LT(m.rolling_mismatch, 0.005);
}

TEST_P(InclineTest, SlidesAboveCriticalAngle) {
  const double theta = 45 * M_PI / 180;  // tan = 1 > 0.7
  ASSERT_GT(std::tan(theta), 3.5 * kMu);
  const Motion m = slide_down(GetParam(), theta);
  EXPECT_NEAR(m.acceleration / (kGravity * (std::sin(theta) - kMu * std::cos(theta))), 1.0, 0.005);
  EXPECT_NEAR(m.angular_acceleration / (2.5 * kMu * kGravity * std::cos(theta) / kRadius), 1.0, 0.005);
  EXPECT_GT(m.rolling_mismatch, 0.3);  // omega R / v = 5 mu cos / (2 (sin - mu cos)) = 0.62
}

INSTANTIATE_TEST_SUITE_P(Backends, InclineTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
