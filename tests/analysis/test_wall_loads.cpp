// Loads on analytic walls for the time series: the walls of a box hold a
// settled pile (the side walls carry part of it by friction), so the loads on
// all walls add up to its weight and their torques about a common point to
// the weight's moment; a sphere held on an incline by friction loads the
// plane with m g, split into normal and tangential parts.
#include <gtest/gtest.h>

#include <cmath>

#include <omp.h>

#include "analysis/wall_loads.hpp"
#include "contact/contact_time.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kGravity = 9.81;

// 48 spheres dropped into a box of five planes; torques about an off-centre point.
SceneSpec pile_in_box(const Vec3d& centre) {
  SceneSpec scene = base_scene(kDensity, kStiffness, 0.1, 0.5);
  scene.effects = kFriction;
  scene.domain_min = {-0.006, -0.006, -0.001};
  scene.domain_max = {0.006, 0.006, 0.02};
  scene.gravity = {0, 0, -kGravity};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1}), plane_wall({-0.005, 0, 0}, {1, 0, 0}),
                 plane_wall({0.005, 0, 0}, {-1, 0, 0}), plane_wall({0, -0.005, 0}, {0, 1, 0}),
                 plane_wall({0, 0.005, 0}, {0, -1, 0})};
  for (Wall& w : scene.walls) w.axis_point = centre;
  ParticleId id = 0;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        scene.particles.push_back(particle(id++, kRadius, {-0.003 + 0.002 * i + 0.0001 * k, -0.003 + 0.002 * j,
                                                           kRadius * (1.2 + 2.4 * k)}));
  scene.time_step = linear_contact_time(kStiffness, stored_sphere_mass(kRadius, kDensity) / 2, 0.1) / 30;
  return scene;
}

TEST(WallLoads, WallsTogetherCarryTheSettledPile) {
  const Vec3d centre{-0.002, 0.001, 0};
  const SceneSpec scene = pile_in_box(centre);
  const double m = stored_sphere_mass(kRadius, kDensity);
  Simulation sim(scene, {Backend::cpu});
  sim.run(std::llround(0.5 / scene.time_step));
  const ParticleSnapshot s = sim.snapshot();
  const std::vector<MeshLoad> loads = wall_loads(scene, sim.walls(), s, sim.wall_contact_history());
  const double weight = m * kGravity * double(s.size());
  ASSERT_LT(std::sqrt(2 * kinetic_energy(s) / (m * double(s.size()))), 1e-4) << "the pile has not settled";
  Vec3d force, torque;
  for (const MeshLoad& l : loads) {
    force += l.force;
    torque += l.torque;
  }
  EXPECT_NEAR(force.z / -weight, 1.0, 1e-3);
  EXPECT_NEAR(force.x / weight, 0.0, 1e-3);
  EXPECT_NEAR(force.y / weight, 0.0, 1e-3);
  EXPECT_GT(-loads[0].force.z, 0.5 * weight) << "the floor carries most of the pile";
  // Moment of the weight about the centre: sum over particles of (x_i - c) x (0, 0, -m g).
  Vec3d moment;
  for (std::size_t i = 0; i < s.size(); ++i) moment += cross(s.position[i] - centre, Vec3d{0, 0, -m * kGravity});
  EXPECT_NEAR(torque.x, moment.x, 1e-3 * weight * 0.005);
  EXPECT_NEAR(torque.y, moment.y, 1e-3 * weight * 0.005);
  EXPECT_NEAR(torque.z, 0.0, 1e-3 * weight * 0.005);
}

// One sphere held on a plane by gravity tilted 10 degrees, friction 0.5 and
// rolling resistance holding it at rest: the wall carries m g exactly, normal
// part m g cos(theta) and tangential part m g sin(theta).
TEST(WallLoads, StickingSphereOnInclineCarriesFriction) {
  SceneSpec scene = base_scene(kDensity, kStiffness, 0.3, 0.5);
  scene.effects = kFriction | kRollingResistance;
  scene.pairs[0].rolling_friction = 0.5;
  scene.domain_min = {-0.004, -0.004, -0.004};
  scene.domain_max = {0.004, 0.004, 0.004};
  const double theta = 10.0 * M_PI / 180.0;
  scene.gravity = {kGravity * std::sin(theta), 0, -kGravity * std::cos(theta)};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  const double m = stored_sphere_mass(kRadius, kDensity);
  scene.particles = {particle(0, kRadius, {0, 0, kRadius - m * kGravity * std::cos(theta) / kStiffness})};
  scene.time_step = linear_contact_time(kStiffness, m, 0.3) / 50;
  Simulation sim(scene, {Backend::cpu});
  sim.run(std::llround(0.1 / scene.time_step));
  const ParticleSnapshot s = sim.snapshot();
  ASSERT_LT(norm(s.velocity[0]), 1e-5);
  const std::vector<MeshLoad> loads = wall_loads(scene, sim.walls(), s, sim.wall_contact_history());
  EXPECT_NEAR(loads[0].force.z / (-m * kGravity * std::cos(theta)), 1.0, 1e-3);
  EXPECT_NEAR(loads[0].force.x / (m * kGravity * std::sin(theta)), 1.0, 1e-2);
}

// 20,000 frictionless spheres pressed into a floor, each by its own depth
// (five blocks of the sum and a part): the floor's load is the sum of the
// linear law's k overlap over them (no velocity, no damping), and the same
// bits on one thread and on three.
TEST(WallLoads, ManySpheresSumToTheLawWhateverTheThreads) {
  SceneSpec scene = base_scene(kDensity, kStiffness, 0.5);
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  ParticleSnapshot s;
  double expected = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double depth = 1e-6 * (1 + i % 97);
    s.id.push_back(ParticleId(i));
    s.material.push_back(0);
    s.radius.push_back(float(kRadius));
    s.mass.push_back(float(stored_sphere_mass(kRadius, kDensity)));
    s.inertia.push_back(0);
    s.position.push_back({0.0001 * (i % 100), 0.0001 * (i / 100), kRadius - depth});
    s.velocity.push_back({});
    s.angular_velocity.push_back({});
    expected += kStiffness * depth;
  }
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<MeshLoad> one = wall_loads(scene, scene.walls, s, {});
  omp_set_num_threads(3);
  const std::vector<MeshLoad> three = wall_loads(scene, scene.walls, s, {});
  omp_set_num_threads(threads);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(-one[0].force.z / expected, 1.0, 1e-12);
  EXPECT_EQ(one[0].force.z, three[0].force.z);
  EXPECT_EQ(one[0].torque.x, three[0].torque.x);
  EXPECT_EQ(one[0].torque.y, three[0].torque.y);
}

// Output reads contact counts and the springs of wall contacts from the
// backend instead of the whole history: both must be what the whole history
// says, on every backend, in the middle of the settling (contacts changing).
class HistoryDigestTest : public testing::TestWithParam<Backend> {};

TEST_P(HistoryDigestTest, CountsAndWallSpringsMatchTheWholeHistory) {
  const SceneSpec scene = pile_in_box({0, 0, 0});
  Simulation sim(scene, {GetParam()});
  sim.run(std::llround(0.1 / scene.time_step));
  const ParticleSnapshot s = sim.snapshot();
  const HostHistory all = sim.history();
  // The springs of the scene's effects only: friction, no rolling resistance.
  EXPECT_EQ(all.tangential.size(), all.partner.size());
  EXPECT_TRUE(all.rolling.empty());
  const ParticleRecords on_walls = sim.wall_contact_history();
  const std::size_t k = std::size_t(all.slots);
  ASSERT_EQ(s.contacts.size(), s.size());
  ASSERT_EQ(on_walls.history.slots, all.slots);
  std::size_t touching = 0, contacts = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    int count = 0;
    bool wall = false;
    for (std::size_t j = 0; j < k; ++j) {
      const ParticleId p = all.partner[i * k + j];
      count += p != kNoPartner;
      wall = wall || (p >= kWallPartnerBase && p != kNoPartner);
    }
    EXPECT_EQ(int(s.contacts[i]), count) << "particle " << s.id[i];
    contacts += std::size_t(count);
    if (!wall) continue;
    ASSERT_LT(touching, on_walls.size());
    EXPECT_EQ(on_walls.id[touching], s.id[i]);
    for (std::size_t j = 0; j < k; ++j) {
      EXPECT_EQ(on_walls.history.partner[touching * k + j], all.partner[i * k + j]);
      const Vec3d a = on_walls.history.tangential[touching * k + j], b = all.tangential[i * k + j];
      EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z) << "particle " << s.id[i] << " slot " << j;
    }
    ++touching;
  }
  EXPECT_EQ(touching, on_walls.size());
  EXPECT_GT(touching, 10u) << "the test needs particles on the walls";
  EXPECT_GT(contacts, s.size()) << "the test needs contacts";
}

INSTANTIATE_TEST_SUITE_P(Backends, HistoryDigestTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
