// Staged walls in the engine, on every backend: a gate that stops acting lets
// the particle resting on it fall exactly as in free fall, and its contact
// history goes; a mesh gate does the same; a floor vibrated at
// Gamma = A w^2 / g < 1 carries a particle in contact, at Gamma > 1 the
// particle lifts off where the floor's deceleration reaches g; a run with
// staged and oscillating walls restarts bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact/contact_time.hpp"
#include "io/restart.hpp"
#include "mesh_test_helpers.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// R = 2^-10 m is exact in fp32, so the stored radius equals the one used here.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;
constexpr double kTwoPi = 6.283185307179586476925;

double mass() { return stored_sphere_mass(kRadius, kDensity); }
double rest_overlap() { return mass() * kGravity / kStiffness; }

SceneSpec scene_with_gravity() {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
  scene.effects = kFriction;
  scene.gravity = {0, 0, -kGravity};
  scene.time_step = linear_contact_time(kStiffness, mass(), kRestitution) / 50;
  return scene;
}

class StagedWallTest : public testing::TestWithParam<Backend> {};

// Contacts with walls or mesh features that hold a history slot.
std::size_t surface_contacts(const Simulation& sim) {
  std::size_t n = 0;
  for (ParticleId p : sim.history().partner) n += p >= kMeshPartnerBase && p != kNoPartner;
  return n;
}

// The particle rests on the gate; from the first step at which the gate is
// no longer active, its contact force is zero and it falls exactly as
// z0 + v0 (t - t0) - g (t - t0)^2 / 2, which velocity Verlet reproduces to
// rounding under a constant force.
void expect_free_fall_after_opening(SceneSpec scene, double t_open, Backend backend) {
  scene.particles = {particle(0, kRadius, {0.0003, -0.0002, kRadius - rest_overlap()})};
  Simulation sim(scene, {backend});
  const double dt = scene.time_step;
  const long long open_step = (long long)std::ceil(t_open / dt);  // first step at or after t_open
  sim.run(open_step - 1);
  ASSERT_LT(sim.time(), t_open);
  ParticleSnapshot s = sim.snapshot();
  EXPECT_NEAR(s.force[0].z, mass() * kGravity, 1e-3 * mass() * kGravity) << "rests on the gate before it opens";
  EXPECT_EQ(surface_contacts(sim), 1u) << "the gate contact keeps a friction history";
  sim.run(1);
  s = sim.snapshot();
  ASSERT_GE(sim.time(), t_open);
  EXPECT_EQ(s.force[0].z, 0.0) << "the open gate still pushes";
  EXPECT_EQ(surface_contacts(sim), 0u) << "the gate contact's history outlives the gate";
  const double t0 = sim.time(), z0 = s.position[0].z, v0 = s.velocity[0].z, x0 = s.position[0].x;
  for (int k = 1; k <= 60; ++k) {
    sim.run(10);
    s = sim.snapshot();
    const double t = sim.time() - t0;
    EXPECT_NEAR(s.position[0].z, z0 + v0 * t - 0.5 * kGravity * t * t, 1e-15) << "t - t0 = " << t;
    EXPECT_NEAR(s.velocity[0].z, v0 - kGravity * t, 1e-13) << "t - t0 = " << t;
    EXPECT_EQ(s.position[0].x, x0);
    EXPECT_EQ(s.force[0].z, 0.0);
  }
}

TEST_P(StagedWallTest, GateOpensIntoFreeFall) {
  SceneSpec scene = scene_with_gravity();
  const double t_open = 400.5 * scene.time_step;
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  Timeline gate;
  gate.active.until = t_open;
  scene.wall_timelines = {gate};
  expect_free_fall_after_opening(scene, t_open, GetParam());
}

TEST_P(StagedWallTest, MeshGateOpensIntoFreeFall) {
  SceneSpec scene = scene_with_gravity();
  const double t_open = 400.5 * scene.time_step;
  MeshMotion motion;
  motion.timeline.active.until = t_open;
  add_mesh(scene.meshes, make_flat_square(4, 0.001, 0.2, Rotation(Vec3d(0, 0, 1), 0), Vec3d(-0.002, -0.002, 0), 3).mesh,
           0, motion);
  expect_free_fall_after_opening(scene, t_open, GetParam());
}

// A floor at z = A sin(w t - pi/2): at rest at its lowest point at t = 0.
SceneSpec vibrated_floor(double gamma, double frequency) {
  SceneSpec scene = scene_with_gravity();
  scene.effects = 0;
  const double w = kTwoPi * frequency, A = gamma * kGravity / (w * w);
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  Timeline shaker;
  shaker.oscillation.amplitude = Vec3d(0, 0, A);
  shaker.oscillation.frequency = frequency;
  shaker.oscillation.phase = -0.5 * M_PI;
  scene.wall_timelines = {shaker};
  // At rest on the floor, pressed by m (g + A w^2).
  scene.particles = {particle(0, kRadius, {0, 0, -A + kRadius - (1 + gamma) * rest_overlap()})};
  return scene;
}

// Below 1 g the floor carries the particle through two periods: its overlap
// is that of a mass pressed by m (g + a_floor), a_floor = -A w^2 sin(w t - pi/2).
TEST_P(StagedWallTest, VibratedFloorBelowOneGCarriesParticle) {
  const double gamma = 0.5, f = 25, w = kTwoPi * f, A = gamma * kGravity / (w * w);
  SceneSpec scene = vibrated_floor(gamma, f);
  Simulation sim(scene, {GetParam()});
  const int steps = int(2 / f / scene.time_step);
  double worst = 0;
  for (int k = 0; k < steps; k += 5) {
    sim.run(5);
    const ParticleSnapshot s = sim.snapshot();
    const double phase = w * sim.time() - 0.5 * M_PI;
    const double floor = A * std::sin(phase), a_floor = -A * w * w * std::sin(phase);
    const double overlap = floor + kRadius - s.position[0].z;
    ASSERT_GT(s.force[0].z, 0.0) << "lost contact at t = " << sim.time();
    worst = std::max(worst, std::abs(overlap - mass() * (kGravity + a_floor) / kStiffness));
  }
  std::printf("[ carried  ] largest overlap error %.3g of m g / k\n", worst / rest_overlap());
  EXPECT_LT(worst, 0.03 * rest_overlap()) << "overlap against m (g + a_floor) / k";
}

// Above 1 g the contact force m (g + a_floor) reaches zero, and the particle
// leaves the floor, where sin(w t - pi/2) = 1 / Gamma.
TEST_P(StagedWallTest, VibratedFloorAboveOneGLiftsOffAtTheAnalyticPhase) {
  const double gamma = 2, f = 25, w = kTwoPi * f;
  SceneSpec scene = vibrated_floor(gamma, f);
  Simulation sim(scene, {GetParam()});
  double lift_off = -1;
  for (int k = 0; k < int(0.75 / f / scene.time_step) && lift_off < 0; ++k) {
    sim.run(1);
    if (sim.snapshot().force[0].z <= 0) lift_off = sim.time();
  }
  ASSERT_GT(lift_off, 0) << "never left the floor";
  const double phase = w * lift_off - 0.5 * M_PI;
  std::printf("[ lift-off ] at phase %.5f rad, analytic asin(1/Gamma) = %.5f rad\n", phase, std::asin(1 / gamma));
  EXPECT_NEAR(phase, std::asin(1 / gamma), 0.005) << "lift-off at t = " << lift_off;
}

// Oscillating floor, a side wall pushed in by a velocity table and a lid
// that acts only for a while, a drum table-driven: restarting halfway gives
// the same bits as the run straight through.
TEST_P(StagedWallTest, RestartWithStagedWallsIsBitwise) {
  SceneSpec scene = vibrated_floor(2.5, 40);
  scene.effects = kFriction;
  scene.walls.push_back(plane_wall({-0.004, 0, 0}, {1, 0, 0}));
  scene.walls.push_back(plane_wall({0, 0, 0.004}, {0, 0, -1}));
  Timeline side, lid;
  side.velocity = make_rate_table({0, 0.005, 0.01}, {Vec3d(), Vec3d(0.3, 0, 0), Vec3d(-0.1, 0, 0)});
  lid.active = {0.004, 0.012};
  scene.wall_timelines.push_back(side);
  scene.wall_timelines.push_back(lid);
  scene.particles = {particle(0, kRadius, {-0.001, 0, 0.001}), particle(1, kRadius, {0.0012, 0.0003, 0.0012}),
                     particle(2, kRadius, {0.0001, -0.0004, 0.003})};
  const long long half = (long long)(0.008 / scene.time_step);
  Simulation straight(scene, {GetParam()});
  straight.run(2 * half);
  Simulation first(scene, {GetParam()});
  first.run(half);
  const Checkpoint c = make_checkpoint(first.snapshot(), first.history(), first.walls(), 0, 1);
  Simulation second(scene, {GetParam()}, nullptr, restart_state(c));
  second.run(half);
  const ParticleSnapshot a = straight.snapshot(), b = second.snapshot();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.position[i].x, b.position[i].x);
    EXPECT_EQ(a.position[i].z, b.position[i].z);
    EXPECT_EQ(a.velocity[i].x, b.velocity[i].x);
    EXPECT_EQ(a.velocity[i].z, b.velocity[i].z);
  }
  // The walls moved: the particles are not where they started.
  EXPECT_GT(norm(a.position[0] - Vec3d(-0.001, 0, 0.001)), 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Backends, StagedWallTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
