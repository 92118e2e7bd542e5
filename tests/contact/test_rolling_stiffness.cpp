// Rolling resistance under Hertz-Mindlin uses the pair's stiffness_rolling.
//
// A sphere resting on a plane under gravity, with rolling resistance but no
// sliding friction, is given a small spin omega_0 about y. Below the cap
// (k_r R theta < mu_r m g) the rolling spring's torque -R k_r xi_r, with
// xi_r = R theta against a wall, is the only torque:
//   I theta'' = -R^2 k_r theta,   period 2 pi sqrt(I / (k_r R^2)) = 2 pi sqrt(2/5 m / k_r).
// Two runs with k_r 1000x apart must show their own periods (before, both
// showed the period of the Mindlin tangential stiffness).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 1e-3, kDensity = 2500, kYoungs = 1e8, kPoisson = 0.3, kGravity = 9.81;
constexpr double kRollingMu = 0.5, kAmplitude = 1e-4;  // rad: k_r R theta stays below 1/5 of the cap

// Time between the first and the third downward zero crossing of omega_y
// (two periods), interpolated within the step.
double spin_period(double stiffness_rolling, Backend backend) {
  SceneSpec scene = base_scene(kDensity, 0, 0.5, 0, ContactModel::hertz_mindlin);
  scene.effects = kRollingResistance;
  scene.materials[0].youngs_modulus = kYoungs;
  scene.materials[0].poisson_ratio = kPoisson;
  scene.pairs[0].stiffness_rolling = stiffness_rolling;
  scene.pairs[0].rolling_friction = kRollingMu;
  scene.gravity = {0, 0, -kGravity};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  const double mass = stored_sphere_mass(kRadius, kDensity);
  // Hertz equilibrium m g = 4/3 E* sqrt(R) delta^1.5, E* of a sphere on its own material.
  const double youngs_eff = kYoungs / (2 * (1 - kPoisson * kPoisson));
  const double delta = std::pow(mass * kGravity / (4.0 / 3.0 * youngs_eff * std::sqrt(kRadius)), 2.0 / 3.0);
  const double omega = std::sqrt(stiffness_rolling / (0.4 * mass));
  ParticleInit p = particle(0, kRadius, {0, 0, kRadius - delta});
  p.angular_velocity = {0, kAmplitude * omega, 0};  // theta(t) = kAmplitude sin(omega t)
  scene.particles = {p};
  scene.time_step = 5e-6;
  scene.contact_time = 5e-4;
  Simulation sim(scene, {backend});
  double previous = p.angular_velocity.y, first = -1;
  int crossings = 0;
  for (long long step = 0; step < 10000000; ++step) {
    sim.run(1);
    const double now = sim.snapshot().angular_velocity[0].y;
    if (previous > 0 && now <= 0) {
      const double t = sim.time() - scene.time_step * now / (now - previous);
      if (crossings == 0) first = t;
      if (++crossings == 3) return (t - first) / 2;
    }
    previous = now;
  }
  return -1;
}

class RollingStiffnessTest : public testing::TestWithParam<Backend> {};

TEST_P(RollingStiffnessTest, HertzSpinOscillatesAtTheRollingSpringPeriod) {
  const double mass = stored_sphere_mass(kRadius, kDensity);
  double periods[2];
  int n = 0;
  for (const double k_r : {0.1, 100.0}) {
    const double expected = 2 * M_PI * std::sqrt(0.4 * mass / k_r);
    periods[n++] = spin_period(k_r, GetParam());
    std::printf("[ measured ] hertz_mindlin, k_r %g N/m: spin period %.6g s (analytic %.6g s)\n", k_r, periods[n - 1],
                expected);
    EXPECT_NEAR(periods[n - 1] / expected, 1.0, 0.01) << "k_r " << k_r;
  }
  EXPECT_NEAR(periods[0] / periods[1], std::sqrt(1000.0), 0.01 * std::sqrt(1000.0));
}

INSTANTIATE_TEST_SUITE_P(Backends, RollingStiffnessTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
