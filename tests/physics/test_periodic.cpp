// Periodic boundaries (domain.periodic): a particle crossing a face comes
// back at the other one at the analytic time with its image count; a contact
// across a face is the contact in the middle of the box; a periodic lattice
// has no edge; momentum is conserved; a restart continues bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "contact/contact_time.hpp"
#include "io/checkpoint.hpp"
#include "io/restart.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// R = 2^-10 m is exact in fp32, so the stored radius equals the one used here.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5;
constexpr unsigned kX = 1u, kY = 2u, kZ = 4u;

double mass() { return stored_sphere_mass(kRadius, kDensity); }
double contact_step() { return linear_contact_time(kStiffness, mass(), kRestitution) / 50; }

SceneSpec periodic_scene(unsigned axes, Vec3d lo, Vec3d hi, double friction = 0) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, friction);
  if (friction > 0) scene.effects = kFriction;
  scene.precision = Precision::fp64;
  scene.domain_min = lo;
  scene.domain_max = hi;
  scene.periodic_axes = axes;
  scene.time_step = contact_step();
  return scene;
}

class PeriodicTest : public testing::TestWithParam<Backend> {};

// Free flight at v = (vx, vy, 0) from x0: the particle crosses the max face
// of x at t = (hi - x0) / vx and the min face of y at t = (y0 - lo) / -vy,
// each in the first step whose end lies past the face, and re-enters at the
// other face with image count +1 in x and -1 in y. Its unwrapped position
// x + n L is x0 + v t throughout.
TEST_P(PeriodicTest, FreeParticleCrossesFacesAtTheAnalyticTime) {
  const double L = 0.01;
  SceneSpec scene = periodic_scene(kX | kY, {0, 0, 0}, {L, L, L});
  const Vec3d x0(0.00601, 0.00401, 0.005), v(0.25, -0.125, 0);
  scene.particles = {particle(0, kRadius, x0, v)};
  scene.time_step = 1e-4;
  Simulation sim(scene, {GetParam()});
  const double dt = scene.time_step;
  const long long cross_x = std::llround(std::ceil((L - x0.x) / v.x / dt));  // 0.01596 s: step 160
  const long long cross_y = std::llround(std::ceil(x0.y / -v.y / dt));       // 0.03208 s: step 321
  long long step = 0;
  auto run_to = [&](long long k) {
    sim.run(k - step);
    step = k;
    return sim.snapshot();
  };
  ParticleSnapshot s = run_to(cross_x - 1);
  EXPECT_LT(s.position[0].x, L);
  EXPECT_EQ(s.image[0].x, 0);
  s = run_to(cross_x);
  EXPECT_EQ(s.image[0].x, 1);
  EXPECT_NEAR(s.position[0].x, x0.x + v.x * double(cross_x) * dt - L, 1e-12);
  s = run_to(cross_y - 1);
  EXPECT_EQ(s.image[0].y, 0);
  EXPECT_GE(s.position[0].y, 0.0);
  s = run_to(cross_y);
  EXPECT_EQ(s.image[0].y, -1);
  EXPECT_NEAR(s.position[0].y, x0.y + v.y * double(cross_y) * dt + L, 1e-12);
  // Five more box lengths in x: image 6, unwrapped position on the line.
  s = run_to(cross_x + std::llround(5 * L / v.x / dt));
  const double t = double(step) * dt;
  EXPECT_EQ(s.image[0].x, 6);
  EXPECT_NEAR(s.position[0].x + s.image[0].x * L, x0.x + v.x * t, 1e-11);
  EXPECT_NEAR(s.position[0].y + s.image[0].y * L, x0.y + v.y * t, 1e-11);
  EXPECT_EQ(s.image[0].z, 0);
  for (double c : {s.position[0].x, s.position[0].y}) {
    EXPECT_GE(c, 0.0);
    EXPECT_LT(c, L);
  }
}

// Two spheres overlapping by 0.2 R across the x face, sliding past each
// other (friction on) as the spring pushes them apart, against the same pair
// in the middle of a box that does not wrap: the same forces at t = 0
// (normal: k delta, from the overlap alone) and the same motion after.
TEST_P(PeriodicTest, ContactAcrossTheFaceIsTheContactInTheMiddle) {
  const double L = 0.01, gap = 0.9 * kRadius;  // centres 1.8 R apart
  SceneSpec across = periodic_scene(kX, {0, 0, 0}, {L, L, L}, 0.5);
  across.particles = {particle(0, kRadius, {gap, 0.005, 0.005}, {0, 0.02, 0}),
                      particle(1, kRadius, {L - gap, 0.005, 0.005}, {0, -0.02, 0.005})};
  SceneSpec middle = across;
  middle.periodic_axes = 0;
  middle.particles = {particle(0, kRadius, {0.5 * L + gap, 0.005, 0.005}, {0, 0.02, 0}),
                      particle(1, kRadius, {0.5 * L - gap, 0.005, 0.005}, {0, -0.02, 0.005})};
  Simulation a(across, {GetParam()}), b(middle, {GetParam()});
  const ParticleSnapshot a0 = a.snapshot(), b0 = b.snapshot();
  const double force = kStiffness * (2 * kRadius - 2 * gap);
  EXPECT_NEAR(a0.force[0].x, force, 1e-9 * force);
  EXPECT_NEAR(a0.force[1].x, -force, 1e-9 * force);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(norm(a0.force[i] - b0.force[i]), 0.0, 1e-9 * force);
  const double speed = 0.03;
  for (int chunk = 0; chunk < 10; ++chunk) {
    a.run(20);
    b.run(20);
    const ParticleSnapshot sa = a.snapshot(), sb = b.snapshot();
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(norm(sa.velocity[i] - sb.velocity[i]), 0.0, 1e-9 * speed) << "step " << sa.step;
      EXPECT_NEAR(norm(sa.angular_velocity[i] - sb.angular_velocity[i]), 0.0, 1e-9 * speed / kRadius);
      const double shift_a = sa.position[i].x + sa.image[i].x * L - across.particles[i].position.x;
      const double shift_b = sb.position[i].x - middle.particles[i].position.x;
      EXPECT_NEAR(shift_a, shift_b, 1e-12);
    }
  }
}

// A square layer of n x n spheres, periodic in x and y, each squeezed by
// eps against its four neighbours and resting on a floor at the static
// overlap m g / k: every particle has the same five contacts (a lattice with
// edges would push its border particles out), so each is in balance at t = 0
// and none moves over 2000 steps.
TEST_P(PeriodicTest, LatticeOnAFloorHasNoEdge) {
  const int n = 4;
  const double eps = 0.01 * kRadius, spacing = 2 * kRadius - eps, L = n * spacing, g = 9.81;
  SceneSpec scene = periodic_scene(kX | kY, {0, 0, -0.002}, {L, L, 0.01}, 0.5);
  scene.gravity = {0, 0, -g};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  const double rest = kRadius - mass() * g / kStiffness;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      scene.particles.push_back(
          particle(ParticleId(j * n + i), kRadius, {(i + 0.5) * spacing, (j + 0.5) * spacing, rest}));
  Simulation sim(scene, {GetParam()});
  const ParticleSnapshot s0 = sim.snapshot();
  const double squeeze = kStiffness * eps, weight = mass() * g;
  for (std::size_t k = 0; k < s0.size(); ++k) {
    EXPECT_EQ(s0.contacts[k], 5) << "particle " << k;
    EXPECT_NEAR(s0.force[k].x, 0.0, 1e-9 * squeeze) << "particle " << k;
    EXPECT_NEAR(s0.force[k].y, 0.0, 1e-9 * squeeze) << "particle " << k;
    EXPECT_NEAR(s0.force[k].z, weight, 1e-9 * weight) << "particle " << k;
  }
  sim.run(2000);
  const ParticleSnapshot s = sim.snapshot();
  for (std::size_t k = 0; k < s.size(); ++k) {
    EXPECT_LT(norm(s.position[k] - scene.particles[k].position), 1e-6 * eps) << "particle " << k;
    EXPECT_EQ(s.image[k].x, 0);
    EXPECT_EQ(s.image[k].y, 0);
  }
}

// Spheres in a box periodic on all three axes, no gravity, no walls,
// colliding with friction: total momentum stays what it was to rounding
// (each contact is computed from both sides with exactly opposite nearest
// image separations), while many particles cross the faces.
SceneSpec colliding_gas(int n_side, double L) {
  SceneSpec scene = periodic_scene(kX | kY | kZ, {0, 0, 0}, {L, L, L}, 0.5);
  const double spacing = L / n_side;
  std::srand(7);
  auto speed = [] { return 0.2 * (double(std::rand()) / RAND_MAX - 0.5); };
  ParticleId id = 0;
  for (int k = 0; k < n_side; ++k)
    for (int j = 0; j < n_side; ++j)
      for (int i = 0; i < n_side; ++i)
        scene.particles.push_back(particle(id++, kRadius, {(i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing},
                                           {speed(), speed(), speed()}));
  return scene;
}

Vec3d momentum(const ParticleSnapshot& s) {
  Vec3d p;
  for (std::size_t i = 0; i < s.size(); ++i) p += s.velocity[i] * double(s.mass[i]);
  return p;
}

TEST_P(PeriodicTest, MomentumIsConservedWhileParticlesCrossTheFaces) {
  const SceneSpec scene = colliding_gas(3, 3 * 2.2 * kRadius);
  Simulation sim(scene, {GetParam()});
  const ParticleSnapshot s0 = sim.snapshot();
  double scale = 0;
  for (std::size_t i = 0; i < s0.size(); ++i) scale += double(s0.mass[i]) * norm(s0.velocity[i]);
  const Vec3d p0 = momentum(s0);
  sim.run(40000);
  const ParticleSnapshot s = sim.snapshot();
  EXPECT_LT(norm(momentum(s) - p0), 1e-13 * scale);
  int crossed = 0;
  for (const ImageCount& n : s.image) crossed += (n.x != 0 || n.y != 0 || n.z != 0) ? 1 : 0;
  EXPECT_GE(crossed, 5);
  double moved = 0;  // the particles did collide: the velocities changed
  for (std::size_t i = 0; i < s.size(); ++i) moved += norm(s.velocity[i] - s0.velocity[i]);
  EXPECT_GT(moved, 0.1 * scale / mass());
}

// A checkpoint of a periodic run, read back, continues bit for bit as the
// run that was not interrupted: positions, velocities and image counts.
TEST_P(PeriodicTest, RestartContinuesBitwise) {
  const SceneSpec scene = colliding_gas(3, 3 * 2.2 * kRadius);
  Simulation whole(scene, {GetParam()});
  whole.run(20000);
  Simulation first(scene, {GetParam()});
  first.run(9000);
  const std::string path = testing::TempDir() + "periodic_restart_" + backend_name(GetParam()) + ".h5";
  write_checkpoint(path, make_checkpoint(first.snapshot(), first.history(), first.walls(), 1, 1));
  const Checkpoint back = read_checkpoint(path);
  ASSERT_EQ(back.particles.image.size(), scene.particles.size());
  Simulation second(scene, {GetParam()}, nullptr, restart_state(back));
  second.run(11000);
  const ParticleSnapshot a = whole.snapshot(), b = second.snapshot();
  ASSERT_EQ(a.size(), b.size());
  int crossed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a.position[i], &b.position[i], sizeof(Vec3d)), 0) << "particle " << i;
    EXPECT_EQ(std::memcmp(&a.velocity[i], &b.velocity[i], sizeof(Vec3d)), 0) << "particle " << i;
    EXPECT_EQ(std::memcmp(&a.image[i], &b.image[i], sizeof(ImageCount)), 0) << "particle " << i;
    crossed += (a.image[i].x != 0 || a.image[i].y != 0 || a.image[i].z != 0) ? 1 : 0;
  }
  EXPECT_GE(crossed, 3);
}

// A scene that does not wrap keeps no image counts: nothing to pay.
TEST_P(PeriodicTest, NonPeriodicRunKeepsNoImageCounts) {
  SceneSpec scene = periodic_scene(0, {0, 0, 0}, {0.01, 0.01, 0.01});
  scene.particles = {particle(0, kRadius, {0.005, 0.005, 0.005})};
  Simulation sim(scene, {GetParam()});
  EXPECT_TRUE(sim.snapshot().image.empty());
}

// Periodic in x, open at zmin: a particle flying along x and falling wraps
// across the x faces (never removed there, never a fault) and is removed when
// it leaves through the open floor; an outlet in the box removes another.
TEST_P(PeriodicTest, WrapsAcrossPeriodicFacesAndLeavesThroughOpenOnes) {
  const double L = 0.01;
  SceneSpec scene = periodic_scene(kX, {0, 0, 0}, {L, L, L});
  scene.open_faces = 1u << 4;  // zmin
  scene.gravity = {0, 0, -9.81};
  OutletRegion box;
  box.min = {0.0005, 0.0075, 0.0005};
  box.max = {0.0025, 0.0095, 0.0095};
  scene.outlets.push_back({"side", box});
  scene.particles = {particle(0, kRadius, {0.008, 0.002, 0.008}, {0.5, 0, 0}),
                     particle(1, kRadius, {0.005, 0.0085, 0.005}, {-0.4, 0, 0})};
  scene.time_step = 1e-4;
  Simulation sim(scene, {GetParam()});
  sim.run(100);  // 10 ms: particle 0 has crossed x = L once, particle 1 has reached the outlet
  ParticleSnapshot s = sim.snapshot();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s.id[0], 0u);
  EXPECT_EQ(s.image[0].x, 1);
  std::vector<RemovedParticle> removed = sim.take_removed();
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0].id, 1u);
  EXPECT_EQ(removed[0].exit, 0);  // the outlet
  sim.run(400);  // 50 ms: fallen 12 mm, through the open floor
  EXPECT_EQ(sim.snapshot().size(), 0u);
  removed = sim.take_removed();
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0].id, 0u);
  EXPECT_EQ(removed[0].exit, 1);  // the open face zmin
}

INSTANTIATE_TEST_SUITE_P(Backends, PeriodicTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
