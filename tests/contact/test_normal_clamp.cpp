// A non-cohesive contact never pulls: a sphere resting against a plane that is
// withdrawn (a gate opened) is pushed while its spring outweighs the dashpot's
// tension and then left behind at the speed it has; it is never dragged.
//
// Reference: the clamped law on the sphere, integrated independently (RK4):
//   m v' = max(0, k delta - gamma (v + V)),   delta' = -(v + V),
// with gamma = 2 zeta sqrt(m k), from delta_0 at rest until delta = 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "contact/restitution.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 1e-3, kDensity = 2500, kStiffness = 1e4, kRestitution = 0.3, kOverlap = 1e-5;

struct Result {
  double speed;           // the sphere's velocity along the wall normal when it has left the wall
  double least_force;     // the smallest normal force it felt in contact
};

double reference_speed(double mass, double wall_speed) {
  const double gamma = 2 * damping_ratio(ContactModel::linear, kRestitution) * std::sqrt(mass * kStiffness);
  double delta = kOverlap, v = 0;
  const double h = 1e-9;
  auto accel = [&](double d, double u) { return std::max(0.0, kStiffness * d - gamma * (u + wall_speed)) / mass; };
  while (delta > 0) {
    const double a1 = accel(delta, v), d1 = -(v + wall_speed);
    const double a2 = accel(delta + 0.5 * h * d1, v + 0.5 * h * a1), d2 = -(v + 0.5 * h * a1 + wall_speed);
    const double a3 = accel(delta + 0.5 * h * d2, v + 0.5 * h * a2), d3 = -(v + 0.5 * h * a2 + wall_speed);
    const double a4 = accel(delta + h * d3, v + h * a3), d4 = -(v + h * a3 + wall_speed);
    delta += h / 6 * (d1 + 2 * d2 + 2 * d3 + d4);
    v += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
  }
  return v;
}

Result withdraw(double wall_speed, Backend backend) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution);
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  scene.walls[0].velocity = {0, 0, -wall_speed};
  scene.particles = {particle(0, kRadius, {0, 0, kRadius - kOverlap})};
  const double mass = stored_sphere_mass(kRadius, kDensity);
  scene.time_step = M_PI * std::sqrt(mass / kStiffness) / 2000;
  scene.contact_time = M_PI * std::sqrt(mass / kStiffness);
  Simulation sim(scene, {backend});
  Result r{0, 1e300};
  for (int step = 0; step < 1000000; ++step) {
    sim.run(1);
    const ParticleSnapshot s = sim.snapshot();
    const double gap = s.position[0].z - (-wall_speed * sim.time());
    if (gap >= kRadius) break;
    r.least_force = std::min(r.least_force, s.force[0].z);
  }
  r.speed = sim.snapshot().velocity[0].z;
  return r;
}

class NormalClampTest : public testing::TestWithParam<Backend> {};

// 0.2 m/s: the spring wins at first (k delta_0 = 0.1 N against gamma V =
// 0.064 N), then the dashpot's tension would; 5 m/s, the gate: the
// tension would win from the start, so the sphere must stay at rest.
TEST_P(NormalClampTest, WithdrawnWallNeverPulls) {
  const double mass = stored_sphere_mass(kRadius, kDensity);
  for (const double wall_speed : {0.2, 5.0}) {
    SCOPED_TRACE("wall speed " + std::to_string(wall_speed));
    const Result r = withdraw(wall_speed, GetParam());
    const double expected = reference_speed(mass, wall_speed);
    std::printf("[ measured ] wall withdrawn at %.1f m/s: sphere leaves at %.6g m/s (reference %.6g), least "
                "normal force %.3g N\n", wall_speed, r.speed, expected, r.least_force);
    EXPECT_GE(r.least_force, 0.0);
    EXPECT_GE(r.speed, 0.0);
    EXPECT_NEAR(r.speed, expected, 0.01 * std::max(expected, 1e-3));
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, NormalClampTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
