// Removal at the scene's exits (engine/particle_removal.hpp), on every
// backend: a particle falling freely from rest is removed at the step its
// centre first reaches an outlet or passes an open face, which velocity
// Verlet predicts in closed form (z_n = z_0 - g (n dt)^2 / 2, exact for a
// constant acceleration); leaving through a closed face is still a fault;
// and the particles that stay, with their forces and contact history, are
// bitwise those of a run in which the removed ones never existed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "support/support.hpp"

namespace gs {
namespace {

class RemovalTest : public testing::TestWithParam<Backend> {
 protected:
  RunOptions options() const {
    RunOptions o;
    o.backend = GetParam();
    return o;
  }
};

constexpr double kG = 9.81, kDt = 1e-4, kRadius = 0.001;

// Five spheres side by side, at rest at different heights, falling freely
// in the base scene's domain [-0.02, 0.02]^3: they never touch.
SceneSpec falling_column() {
  SceneSpec s = test::base_scene(2500, 2000, 0.5);
  s.gravity = Vec3d(0, 0, -kG);
  s.time_step = kDt;
  for (int k = 0; k < 5; ++k)
    s.particles.push_back(test::particle(ParticleId(k), kRadius, Vec3d(-0.015 + 0.0075 * k, 0, 0.015 - 0.0041 * k)));
  return s;
}

// The first step n whose centre height z0 - g (n dt)^2 / 2 passes `level`
// (strictly below it, or down to it when `inclusive`); the test needs it not
// to be decided by rounding.
long long predicted_step(double z0, double level, bool inclusive) {
  auto z = [&](long long n) { return z0 - 0.5 * kG * double(n * n) * kDt * kDt; };
  long long n = 0;
  while (inclusive ? z(n) > level : z(n) >= level) ++n;
  EXPECT_GT(std::fabs(z(n) - level), 1e-9) << "the crossing is too close to a step boundary for this test";
  EXPECT_GT(std::fabs(z(n - 1) - level), 1e-9) << "the crossing is too close to a step boundary for this test";
  return n;
}

std::map<ParticleId, RemovedParticle> by_id(const std::vector<RemovedParticle>& removed) {
  std::map<ParticleId, RemovedParticle> m;
  for (const RemovedParticle& r : removed) EXPECT_TRUE(m.emplace(r.id, r).second) << "particle " << r.id << " twice";
  return m;
}

TEST_P(RemovalTest, FreeFallThroughAnOpenFloorAtThePredictedStep) {
  SceneSpec s = falling_column();
  s.open_faces = 1u << 4;  // zmin
  const std::vector<ParticleInit> created = s.particles;
  Simulation sim(s, options());
  long long first = 1LL << 40, last = 0;
  for (const ParticleInit& p : created) {
    first = std::min(first, predicted_step(p.position.z, s.domain_min.z, false));
    last = std::max(last, predicted_step(p.position.z, s.domain_min.z, false));
  }
  // Stepped in stretches that end one step before and at the first removal.
  sim.run(first - 1);
  EXPECT_EQ(sim.particle_count(), 5);
  sim.run(1);
  EXPECT_EQ(sim.particle_count(), 4);
  sim.run(last - first);
  EXPECT_EQ(sim.particle_count(), 0);
  const auto removed = by_id(sim.take_removed());
  ASSERT_EQ(removed.size(), created.size());
  for (const ParticleInit& p : created) {
    const RemovedParticle& r = removed.at(p.id);
    EXPECT_EQ(r.step, predicted_step(p.position.z, s.domain_min.z, false)) << "particle " << p.id;
    EXPECT_EQ(r.exit, 0);  // the only exit: domain.zmin
    EXPECT_EQ(double(r.mass), test::stored_sphere_mass(kRadius, 2500));
  }
  EXPECT_TRUE(sim.take_removed().empty()) << "handed out twice";
}

TEST_P(RemovalTest, LeavingThroughAClosedFaceIsStillAFault) {
  SceneSpec s = falling_column();
  s.open_faces = 1u << 5;  // zmax open, the floor closed
  Simulation sim(s, options());
  try {
    sim.run(predicted_step(s.particles[0].position.z, s.domain_min.z, false));
    FAIL() << "no fault";
  } catch (const SimulationFault& f) {
    EXPECT_NE(std::string(f.what()).find("left the domain"), std::string::npos) << f.what();
    EXPECT_NE(std::string(f.what()).find("domain.open"), std::string::npos) << f.what();  // what to do about it
  }
}

// The same level, z = -0.005, as the top of a box, of a cylinder along z and
// as a half-space below it: a centre on the boundary counts as inside.
TEST_P(RemovalTest, FreeFallIntoAnOutletOfEachKindAtThePredictedStep) {
  constexpr double kLevel = -0.005;
  std::vector<OutletRegion> regions(3);
  regions[0].kind = OutletRegion::Kind::box;
  regions[0].min = Vec3d(-0.02, -0.02, -0.01);
  regions[0].max = Vec3d(0.02, 0.02, kLevel);
  regions[1].kind = OutletRegion::Kind::cylinder;
  regions[1].point = Vec3d(0, 0, -0.012);
  regions[1].direction = Vec3d(0, 0, 1);
  regions[1].radius = 0.019;
  regions[1].length = kLevel + 0.012;
  regions[2].kind = OutletRegion::Kind::half_space;
  regions[2].point = Vec3d(0.3, -0.2, kLevel);
  regions[2].direction = Vec3d(0, 0, -1);
  for (const OutletRegion& region : regions) {
    SceneSpec s = falling_column();
    s.outlets.push_back({"out", region});
    s.open_faces = 1u << 1;  // xmax: an exit after the outlet, which no particle reaches
    const std::vector<ParticleInit> created = s.particles;
    Simulation sim(s, options());
    long long last = 0;
    for (const ParticleInit& p : created) last = std::max(last, predicted_step(p.position.z, kLevel, true));
    sim.run(last);
    EXPECT_EQ(sim.particle_count(), 0) << "outlet kind " << int(region.kind);
    const auto removed = by_id(sim.take_removed());
    ASSERT_EQ(removed.size(), created.size());
    for (const ParticleInit& p : created) {
      EXPECT_EQ(removed.at(p.id).step, predicted_step(p.position.z, kLevel, true))
          << "particle " << p.id << ", outlet kind " << int(region.kind);
      EXPECT_EQ(removed.at(p.id).exit, 0);
    }
  }
}

// A frictional bed settling against a wall, beside a column that falls into
// an outlet: once the column is gone the bed's particles, their forces and
// their contact history are bitwise those of the bed alone. The compaction
// must carry every field and history slot of the staying particles, keep
// their sums in canonical order, and leave nothing of the removed ones.
// Gravity is along -x, so that the column and the bed share heights and
// stand interleaved in memory (cells are ordered by z first).
TEST_P(RemovalTest, TheStayingParticlesAreThoseOfARunWithoutTheRemovedOnes) {
  SceneSpec bed = test::base_scene(2500, 2000, 0.5, 0.5);
  bed.effects = kFriction | kRollingResistance;
  bed.pairs[0].rolling_friction = 0.1;
  bed.gravity = Vec3d(-kG, 0, 0);
  bed.time_step = 1.5e-5;  // 0.09 of the particle-particle contact time
  bed.walls.push_back(test::plane_wall(Vec3d(-0.015, 0, 0), Vec3d(1, 0, 0)));
  bed.wall_names.push_back("floor");
  // The column's ids come first, so that in memory it starts before the bed.
  SceneSpec with_column = bed;
  ParticleId id = 0;
  for (int k = 0; k < 6; ++k)  // falling at 1 m/s into the outlet, one after another
    with_column.particles.push_back(test::particle(
        id++, kRadius, Vec3d(0.002 + 0.0025 * k, 0.01 + 0.003 * (k % 2), -0.015 + 0.0021 * k), Vec3d(-1, 0, 0)));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        bed.particles.push_back(test::particle(
            id++, kRadius, Vec3d(-0.0139 + 0.0021 * i, -0.004 + 0.0021 * j + 0.0001 * i, -0.016 + 0.0021 * k)));
  with_column.particles.insert(with_column.particles.end(), bed.particles.begin(), bed.particles.end());
  OutletRegion box;
  box.min = Vec3d(-0.01, 0.005, -0.02);
  box.max = Vec3d(-0.005, 0.018, 0.02);
  with_column.outlets.push_back({"chute", box});

  constexpr long long kSteps = 2000;  // the column is gone after ~1250
  Simulation alone(bed, options()), beside(with_column, options());
  alone.run(kSteps);
  beside.run(kSteps);
  EXPECT_EQ(beside.take_removed().size(), 6u);
  const ParticleSnapshot a = alone.snapshot(), b = beside.snapshot();
  ASSERT_EQ(b.size(), bed.particles.size());
  EXPECT_TRUE(test::same_bits(a.id, b.id));
  EXPECT_TRUE(test::same_bits(a.position, b.position));
  EXPECT_TRUE(test::same_bits(a.velocity, b.velocity));
  EXPECT_TRUE(test::same_bits(a.angular_velocity, b.angular_velocity));
  EXPECT_TRUE(test::same_bits(a.orientation, b.orientation));
  EXPECT_TRUE(test::same_bits(a.force, b.force));
  EXPECT_TRUE(test::same_bits(a.torque, b.torque));
  EXPECT_TRUE(test::same_bits(a.contacts, b.contacts));
  long long contacts = 0;
  for (std::uint16_t c : a.contacts) contacts += c;
  EXPECT_GT(contacts, 48) << "the bed should be in contact (floor and neighbours)";
  const HostHistory ha = alone.history(), hb = beside.history();
  EXPECT_TRUE(test::same_bits(ha.partner, hb.partner));
  EXPECT_TRUE(test::same_bits(ha.tangential, hb.tangential));
  EXPECT_TRUE(test::same_bits(ha.rolling, hb.rolling));
}

INSTANTIATE_TEST_SUITE_P(Backends, RemovalTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
