// A sphere's angular velocity is kept only by a run where something can turn
// it (friction or rolling resistance makes torques) or where a particle
// starts spinning (core/particle_fields.hpp, kAngularVelocities). Without
// either, every spin stays zero: the run keeps none (24 bytes per particle
// fewer, and none forwarded to ghosts) and its output reads zeros. No
// frictionless force depends on a spin, so a sphere started spinning keeps
// its spin unchanged and moves as it would without it.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "scene/scene_time_step.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

class SpinTest : public testing::TestWithParam<Backend> {};

// Two frictionless spheres meeting obliquely over a floor, under gravity.
SceneSpec glancing() {
  SceneSpec scene = base_scene(2500, 1000, 0.5);
  scene.gravity = {0, 0, -9.81};
  scene.walls.push_back(plane_wall({0, 0, -0.01}, {0, 0, 1}));
  scene.particles.push_back(particle(0, 0.001, {-0.003, 0, -0.009}, {0.3, 0, 0}));
  scene.particles.push_back(particle(1, 0.001, {0.003, 0.0012, -0.009}, {-0.3, 0, 0}));
  scene.contact_time = critical_contact_time(scene);
  scene.time_step = 0.02 * scene.contact_time;
  return scene;
}

TEST_P(SpinTest, FrictionlessRunsKeepNoneAndASpinChangesNoMotion) {
  const SceneSpec plain = glancing();
  SceneSpec spun = glancing();
  const Vec3d spin{20, -50, 30};
  spun.particles[0].angular_velocity = spin;
  EXPECT_EQ(particle_fields_kept(plain) & kAngularVelocities, 0u);
  EXPECT_NE(particle_fields_kept(spun) & kAngularVelocities, 0u);
  SceneSpec rough = glancing();
  rough.effects = kFriction;
  EXPECT_NE(particle_fields_kept(rough) & kAngularVelocities, 0u);

  Simulation a(plain, {GetParam()}), b(spun, {GetParam()});
  a.run(3000);
  b.run(3000);
  const ParticleSnapshot sa = a.snapshot(), sb = b.snapshot();
  ASSERT_EQ(sa.size(), 2u);
  ASSERT_EQ(sb.size(), 2u);
  // They met each other and the floor: both velocities changed.
  EXPECT_GT(std::abs(sa.velocity[0].x - 0.3), 0.01);
  EXPECT_GT(std::abs(sa.velocity[1].y), 1e-4);
  ASSERT_EQ(sa.angular_velocity.size(), 2u) << "the output of a run that keeps no spin reads zeros";
  for (const Vec3d& w : sa.angular_velocity) EXPECT_EQ(norm2(w), 0.0);
  EXPECT_EQ(sb.angular_velocity[0].x, spin.x) << "nothing turns a frictionless sphere";
  EXPECT_EQ(sb.angular_velocity[0].y, spin.y);
  EXPECT_EQ(sb.angular_velocity[0].z, spin.z);
  EXPECT_EQ(norm2(sb.angular_velocity[1]), 0.0);
  EXPECT_TRUE(same_bits(sa.position, sb.position));
  EXPECT_TRUE(same_bits(sa.velocity, sb.velocity));
  EXPECT_TRUE(same_bits(sa.force, sb.force));
}

INSTANTIATE_TEST_SUITE_P(Backends, SpinTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
