// A sphere resting on a plane wall under gravity: it settles at the static
// overlap m g / k and then stays put, with friction and rolling resistance on
// (their springs must not creep) and in both force precisions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_time.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// R = 2^-10 m is exact in fp32, so the stored radius equals the one used here.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;

double mass() { return stored_sphere_mass(kRadius, kDensity); }
double static_overlap() { return mass() * kGravity / kStiffness; }  // ~1e-7 m = 1e-4 R
double natural_frequency() { return std::sqrt(kStiffness / mass()); }

SceneSpec resting_scene(Precision precision, double height) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
  scene.pairs[0].rolling_friction = 0.1;
  scene.effects = kFriction | kRollingResistance;
  scene.precision = precision;
  scene.domain_min = {-0.004, -0.004, -0.004};
  scene.domain_max = {0.004, 0.004, 0.004};
  scene.gravity = {0, 0, -kGravity};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  scene.particles = {particle(0, kRadius, {0.001, -0.0005, height})};
  scene.time_step = linear_contact_time(kStiffness, mass(), kRestitution) / 50;
  return scene;
}

class RestingTest : public testing::TestWithParam<Backend> {};

// Dropped from touching (zero overlap) at rest, the sphere bounces on the
// spring, the dashpot damps it (zeta = 0.22: e^-40 after 0.02 s) and it comes
// to rest with k delta = m g.
TEST_P(RestingTest, SettlesAtStaticOverlap) {
  for (const Precision precision : {Precision::fp64, Precision::fp32}) {
    SCOPED_TRACE(precision_name(precision));
    const SceneSpec scene = resting_scene(precision, kRadius);
    Simulation sim(scene, {GetParam()});
    sim.run(std::llround(0.02 / scene.time_step));
    const ParticleSnapshot s = sim.snapshot();
    EXPECT_NEAR((kRadius - s.position[0].z) / static_overlap(), 1.0, 1e-6);
    EXPECT_LT(norm(s.velocity[0]), 1e-6 * static_overlap() * natural_frequency());
    EXPECT_EQ(s.position[0].x, 0.001);  // nothing pushes sideways
    EXPECT_EQ(s.position[0].y, -0.0005);
  }
}

// Placed at the static overlap, the sphere must not move over 1e5 steps.
// Bound: 1e-5 of the static overlap delta (1e-12 m) for the position and
// 1e-5 delta omega_0 (1e-8 m/s, against g dt = 6e-5 m/s gained in one step of
// free fall) for the speed. Any error of physical consequence (a force sign,
// gravity kicked twice, a half kick with stale forces, energy fed in by the
// dashpot or the friction and rolling springs creeping) moves it by a
// sizeable fraction of delta. Rounding alone moves it by the force error over
// k: ~1e-12 delta in fp64, ~1e-7 delta in fp32 (overlap and force rounded to
// fp32), both far below the bound.
TEST_P(RestingTest, StaysPutFor1e5Steps) {
  for (const Precision precision : {Precision::fp64, Precision::fp32}) {
    SCOPED_TRACE(precision_name(precision));
    const SceneSpec scene = resting_scene(precision, kRadius - static_overlap());
    Simulation sim(scene, {GetParam()});
    const Vec3d start = scene.particles[0].position;
    double max_shift = 0, max_speed = 0, max_spin = 0;
    for (int chunk = 0; chunk < 100; ++chunk) {
      sim.run(1000);
      const ParticleSnapshot s = sim.snapshot();
      max_shift = std::max(max_shift, norm(s.position[0] - start));
      max_speed = std::max(max_speed, norm(s.velocity[0]));
      max_spin = std::max(max_spin, norm(s.angular_velocity[0]));
    }
    EXPECT_EQ(sim.step_count(), 100000);
    EXPECT_LT(max_shift, 1e-5 * static_overlap());
    EXPECT_LT(max_speed, 1e-5 * static_overlap() * natural_frequency());
    EXPECT_EQ(max_spin, 0.0);  // no tangential force, no rolling: no torque at all
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, RestingTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
