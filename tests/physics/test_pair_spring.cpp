// The tangential spring of a particle pair lives as long as its contact,
// whatever the engine does with its memory meanwhile (docs/DESIGN.md,
// contact/contact_slots.hpp): Verlet list rebuilds, memory re-sorts.
//
// Eight spheres rest under gravity on eight frozen ones, each set spinning
// at omega0 about a horizontal axis. The contact sticks (the spring stays
// below the Coulomb cap), so the spring s (the contact point's tangential
// displacement) obeys, with the sphere's translation and rotation both
// driven by F = -k_t s at lever L = R - delta / 2 (particle_kinematics),
//   s'' = -Omega^2 s,   Omega^2 = k_t (1 / m + L^2 / I),   s'(0) = omega0 L,
// and the spin about the axis is
//   omega(t) = omega0 (1 - a (1 - cos Omega t)),   a = k_t L^2 / (I Omega^2) = 5/7:
// at half a period it has turned round, to -3/7 omega0. A spring lost at a
// rebuild restarts from zero: the spin then stays near omega0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "support/support.hpp"

namespace gs::test {
namespace {

// R = 2^-10 m is exact in fp32, so the stored radius equals the one used here.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kFrictionCoefficient = 0.5,
                 kGravity = 9.81;
constexpr int kPairs = 8;

double mass() { return stored_sphere_mass(kRadius, kDensity); }
double inertia() { return 0.4 * mass() * kRadius * kRadius; }
double overlap() { return mass() * kGravity / kStiffness; }  // static: k_n delta = m g
double lever() { return kRadius - 0.5 * overlap(); }
double stiffness_tangential() { return kStiffness * 2.0 / 7.0; }  // base_scene's
double omega_spring() { return std::sqrt(stiffness_tangential() * (1 / mass() + lever() * lever() / inertia())); }
// Half the largest stick displacement: the spring peaks at half the Coulomb cap.
double omega0() { return 0.5 * kFrictionCoefficient * mass() * kGravity / stiffness_tangential() * omega_spring() / lever(); }
Vec3d spin_axis(int p) { return {std::cos(0.7 * p), std::sin(0.7 * p), 0}; }

// Pair p: frozen sphere id 2p+1 below, spinning sphere 2p on it, pairs 4 R
// apart on a 4 x 2 grid, listed in reverse so that a re-sort by cell moves
// them. No damping (restitution 1): the law is the undamped spring.
SceneSpec spinning_pairs() {
  SceneSpec scene = base_scene(kDensity, kStiffness, 1.0, kFrictionCoefficient);
  scene.effects = kFriction;
  scene.gravity = {0, 0, -kGravity};
  scene.frozen_particles = true;
  for (int p = kPairs - 1; p >= 0; --p) {
    const Vec3d at{(p % 4 - 1.5) * 4 * kRadius, (p / 4 - 0.5) * 4 * kRadius, 0};
    ParticleInit below = particle(ParticleId(2 * p + 1), kRadius, at);
    below.frozen = 1;
    ParticleInit above = particle(ParticleId(2 * p), kRadius, at + Vec3d{0, 0, 2 * kRadius - overlap()});
    above.angular_velocity = spin_axis(p) * omega0();
    scene.particles.push_back(above);
    scene.particles.push_back(below);
  }
  scene.time_step = 2 * M_PI / omega_spring() / 400;
  return scene;
}

class PairSpringTest : public testing::TestWithParam<Backend> {};

// Half a period with the list rebuilt at every step (no skin) and memory
// re-sorted by cell at step 50 (the spheres listed against the cells'
// order, so the re-sort moves every one, springs near their peak; the ones
// after it find memory in order already): every sphere's spin has turned
// round as the spring's law says.
TEST_P(PairSpringTest, SurvivesARebuildEveryStepAndAReSort) {
  SceneSpec scene = spinning_pairs();
  scene.verlet_skin = 0;
  RunOptions options{GetParam()};
  options.reorder_interval = 50;
  Simulation sim(scene, options);
  sim.run(200);
  EXPECT_GE(sim.neighbour_builds(), 200);
  const ParticleSnapshot s = sim.snapshot();
  const double t = 200 * scene.time_step, a = stiffness_tangential() * lever() * lever() / (inertia() * omega_spring() * omega_spring());
  EXPECT_NEAR(a, 5.0 / 7.0, 1e-3);
  const double expected = 1 - a * (1 - std::cos(omega_spring() * t));  // in units of omega0: -3/7
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.id[i] % 2 == 1) continue;  // frozen
    const int p = int(s.id[i] / 2);
    EXPECT_NEAR(dot(s.angular_velocity[i], spin_axis(p)) / omega0(), expected, 1e-4) << "sphere " << s.id[i];
  }
}

// The same run with the default skin and re-sort schedule (the list built
// once, memory never re-sorted) computes the same bits as that one.
TEST_P(PairSpringTest, RebuildScheduleChangesNoBit) {
  const SceneSpec scene = spinning_pairs();
  SceneSpec no_skin = scene;
  no_skin.verlet_skin = 0;
  RunOptions every_step{GetParam()};
  every_step.reorder_interval = 50;
  Simulation rebuilt(no_skin, every_step), kept(scene, RunOptions{GetParam()});
  rebuilt.run(300);
  kept.run(300);
  EXPECT_LT(kept.neighbour_builds(), 5);
  const ParticleSnapshot a = rebuilt.snapshot(), b = kept.snapshot();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.id[i], b.id[i]);
    EXPECT_EQ(std::memcmp(&a.angular_velocity[i], &b.angular_velocity[i], sizeof(Vec3d)), 0) << "sphere " << a.id[i];
    EXPECT_EQ(std::memcmp(&a.velocity[i], &b.velocity[i], sizeof(Vec3d)), 0) << "sphere " << a.id[i];
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, PairSpringTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
