// Frozen particles (docs/SCENES.md, `frozen`): a frozen sphere in free space
// carries a sphere resting on it under gravity. It must not move at all (no
// integration: gravity and the contact's load would otherwise pull it down),
// and the resting sphere must feel the reaction of a fixed support: it settles
// at the static overlap m g / k, as on a plane wall (tests/physics/test_resting.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// R = 2^-10 m is exact in fp32, so the stored radius equals the one used here.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;

double mass() { return stored_sphere_mass(kRadius, kDensity); }
double static_overlap() { return mass() * kGravity / kStiffness; }

// Sphere 0 frozen at the origin, sphere 1 on top of it, touching at rest
// (zero overlap), slightly off the vertical line so that the contact is not
// a one-dimensional special case; gravity along -z. No wall anywhere.
SceneSpec frozen_support(Precision precision) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
  scene.effects = kFriction;
  scene.precision = precision;
  scene.domain_min = {-0.004, -0.004, -0.004};
  scene.domain_max = {0.004, 0.004, 0.006};
  scene.gravity = {0, 0, -kGravity};
  ParticleInit base = particle(0, kRadius, {0, 0, 0});
  base.frozen = 1;
  scene.particles = {base, particle(1, kRadius, {0, 0, 2 * kRadius})};
  scene.frozen_particles = true;
  scene.time_step = linear_contact_time(kStiffness, mass(), kRestitution) / 50;
  return scene;
}

class FrozenTest : public testing::TestWithParam<Backend> {};

// After 0.05 s (the dashpot has damped the bounce by far more than e^-40),
// the frozen sphere is exactly where it was created, at rest, and the other
// rests on it at the overlap where the spring carries its weight.
TEST_P(FrozenTest, CarriesALoadWithoutMoving) {
  for (const Precision precision : {Precision::fp64, Precision::fp32}) {
    SCOPED_TRACE(precision_name(precision));
    const SceneSpec scene = frozen_support(precision);
    Simulation sim(scene, {GetParam()});
    sim.run(std::llround(0.05 / scene.time_step));
    const ParticleSnapshot s = sim.snapshot();
    ASSERT_EQ(s.size(), 2u);
    const std::size_t frozen = s.id[0] == 0 ? 0 : 1, resting = 1 - frozen;
    EXPECT_EQ(s.position[frozen].x, 0.0);
    EXPECT_EQ(s.position[frozen].y, 0.0);
    EXPECT_EQ(s.position[frozen].z, 0.0);
    EXPECT_EQ(norm(s.velocity[frozen]), 0.0);
    EXPECT_EQ(norm(s.angular_velocity[frozen]), 0.0);
    // The reaction: k delta = m g, to 1e-5 of delta (fp32 forces round at ~1e-7).
    EXPECT_NEAR((2 * kRadius - s.position[resting].z) / static_overlap(), 1.0, 1e-5);
    EXPECT_LT(norm(s.velocity[resting]), 1e-6);
  }
}

// The same sphere set in motion (thrown down onto the frozen one at 0.1 m/s,
// a load of many times its weight at the impact) still does not move it.
TEST_P(FrozenTest, StaysPutUnderAnImpact) {
  SceneSpec scene = frozen_support(Precision::fp64);
  scene.particles[1].position.z = 2 * kRadius + 0.0005;
  scene.particles[1].velocity = {0.01, 0, -0.1};
  Simulation sim(scene, {GetParam()});
  for (int chunk = 0; chunk < 20; ++chunk) {
    sim.run(200);
    const ParticleSnapshot s = sim.snapshot();
    const std::size_t frozen = s.id[0] == 0 ? 0 : 1;
    ASSERT_EQ(norm(s.position[frozen]), 0.0) << "step " << sim.step_count();
    ASSERT_EQ(norm(s.velocity[frozen]), 0.0) << "step " << sim.step_count();
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, FrozenTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
