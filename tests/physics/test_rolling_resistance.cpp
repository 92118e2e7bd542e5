// Rolling resistance brings a sphere rolling on a flat plane to rest at the
// distance the rolling torque predicts.
//
// contact_law.hpp / tangential_spring.hpp: once the rolling spring has reached
// its cap (after a rotation of mu_r |f_n| / (k_r R), ~4e-5 rad here), the
// torque on a rolling sphere is the constant mu_r R_eff |f_n| against omega,
// with R_eff = R against a wall and |f_n| = m g at rest on the plane. With v
// along +x, omega along +y and the friction force F along x at the contact
// point -R z:
//   m dv/dt = F,   I domega/dt = -R F - mu_r R m g,   dv/dt = R domega/dt,
// and I = 2/5 m R^2 give dv/dt = -5/7 mu_r g: it stops after
//   t = 7 v0 / (5 mu_r g)   at   d = 7 v0^2 / (10 mu_r g).
// Friction keeps it rolling as long as mu > 5/7 mu_r.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_time.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;
constexpr double kMu = 0.5, kRollingMu = 0.1, kSpeed = 0.1;

class RollingResistanceTest : public testing::TestWithParam<Backend> {};

// Tolerance 0.5% on distance and time: the rigid-body model neglects the
// overlap (delta / R ~ 1e-4) and the spring transients at the start and at
// the stop (~1e-5 of d); mass and inertia are fp32.
TEST_P(RollingResistanceTest, StopsAtPredictedDistance) {
  const double mass = stored_sphere_mass(kRadius, kDensity);
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, kMu);
  scene.pairs[0].rolling_friction = kRollingMu;
  scene.effects = kFriction | kRollingResistance;
  scene.domain_min = {-0.004, -0.004, -0.004};
  scene.domain_max = {0.012, 0.004, 0.004};
  scene.gravity = {0, 0, -kGravity};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  ParticleInit p = particle(0, kRadius, {0, 0, kRadius - mass * kGravity / kStiffness}, {kSpeed, 0, 0});
  p.angular_velocity = {0, kSpeed / kRadius, 0};  // rolling without slipping
  scene.particles = {p};
  scene.time_step = linear_contact_time(kStiffness, mass, kRestitution) / 50;
  ASSERT_GT(kMu, 5.0 / 7.0 * kRollingMu);

  const double distance = 7 * kSpeed * kSpeed / (10 * kRollingMu * kGravity);  // 7.1 mm
  const double stop_time = 7 * kSpeed / (5 * kRollingMu * kGravity);            // 0.14 s
  Simulation sim(scene, {GetParam()});
  // Half way in time it has half its speed and still rolls without slipping.
  sim.run(std::llround(0.5 * stop_time / scene.time_step));
  const ParticleSnapshot half = sim.snapshot();
  EXPECT_NEAR(half.velocity[0].x / (0.5 * kSpeed), 1.0, 0.005);
  EXPECT_NEAR(half.angular_velocity[0].y * kRadius / half.velocity[0].x, 1.0, 0.005);

  // Then to the stop: the first time v_x <= 0.
  ParticleSnapshot s = half;
  while (s.velocity[0].x > 0 && s.time < 2 * stop_time) {
    sim.run(10);
    s = sim.snapshot();
  }
  EXPECT_NEAR(s.position[0].x / distance, 1.0, 0.005);
  EXPECT_NEAR(s.time / stop_time, 1.0, 0.005);

  // At rest it stays there: the rolling spring holds it. Rolling back under the
  // capped torque for 0.02 s would reach 5/7 mu_r g 0.02 s = 14 mm/s and move
  // 0.14 mm; the spring's own oscillation is below 1e-7 m and 1e-5 m/s.
  const double x_stop = s.position[0].x;
  sim.run(std::llround(0.02 / scene.time_step));
  s = sim.snapshot();
  EXPECT_LT(std::fabs(s.position[0].x - x_stop), 1e-4 * distance);
  EXPECT_LT(std::fabs(s.velocity[0].x), 1e-3 * kSpeed);
}

INSTANTIATE_TEST_SUITE_P(Backends, RollingResistanceTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
