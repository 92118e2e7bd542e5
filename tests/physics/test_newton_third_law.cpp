// Newton's third law with no rounding left over: the two spheres of a
// contact each compute it from their own side (engine/force_kernel.hpp), and
// every quantity seen from the partner is exactly the negation or exactly the
// same, so the forces must be exactly opposite (as numbers: a zero may differ
// in sign), and with equal radii the frictional torques exactly equal
// (tau = -(L n) x f_t on both). Separate pairs, each sphere touching only its
// partner, so a sphere's force is its one contact's. Random radii, overlaps,
// directions, velocities and spins; like and unlike materials; the springs
// carried over a few steps, some pairs sliding; pairs across a periodic face
// too. It failed when the lever arms' spins were summed with one fused
// multiply-add (the partner's product rounded first, so from the other side
// the other product): forces then differed in their last bits; and when one
// side's material alone chose the pair's parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "scene/scene_time_step.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kSliding = 0.5;
constexpr int kPairs = 48, kPeriodicPairs = 4, kSteps = 20;
constexpr double kSpacing = 0.008;  // between pairs' centres: no contact across pairs

struct Case {
  Backend backend;
  Precision precision;
  ContactModel model;
  unsigned effects;
};

Vec3d random_unit(std::mt19937_64& g) {
  std::normal_distribution<double> n;
  const Vec3d v{n(g), n(g), n(g)};
  return v * (1 / norm(v));
}

// kPairs pairs on a 4 x 4 x 3 grid, then kPeriodicPairs across the x face
// (the box wraps along x) in the fourth layer. Overlaps of 0.2-1 % of the
// two radii, relative speeds up to 0.01 m/s, against overlap / contact time
// of about 0.05 m/s: the pairs stay in contact over the 20 steps (0.2 contact
// times); spins up to 400 rad/s slide some of them at the Coulomb cap. With
// equal_radii every sphere is 1 mm.
SceneSpec pairs_scene(const Case& c, bool equal_radii, std::uint64_t seed) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, kSliding, c.model);
  scene.precision = c.precision;
  scene.effects = c.effects;
  scene.pairs[0].rolling_friction = 0.1;
  scene.pairs[0].cohesion_energy_density = 2e3;
  add_second_material(scene);  // unlike pairs take the (m, n) entry from both sides
  scene.domain_min = {0, 0, 0};
  scene.domain_max = {4 * kSpacing, 4 * kSpacing, 4 * kSpacing};
  scene.periodic_axes = 1u;  // x
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(0, 1);
  ParticleId next = 0;
  for (int p = 0; p < kPairs + kPeriodicPairs; ++p) {
    const double ra = equal_radii ? 0.001 : 0.0008 + 0.0004 * u(g), rb = equal_radii ? 0.001 : 0.0008 + 0.0004 * u(g);
    const Vec3d dir = random_unit(g);
    const double distance = (ra + rb) * (1 - (0.002 + 0.008 * u(g)));
    // A periodic pair sits on the x face: its halves lie on either side.
    const Vec3d centre = p < kPairs ? Vec3d{(p % 4 + 0.5) * kSpacing, (p / 4 % 4 + 0.5) * kSpacing,
                                            (p / 16 + 0.5) * kSpacing}
                                    : Vec3d{0, (p - kPairs + 0.5) * kSpacing, 3.5 * kSpacing};
    Vec3d xa = centre + dir * (0.5 * distance), xb = centre - dir * (0.5 * distance);
    if (p >= kPairs) {  // back into the box across the face
      if (xa.x < 0) xa.x += scene.domain_max.x;
      if (xb.x < 0) xb.x += scene.domain_max.x;
    }
    ParticleInit a = particle(next++, ra, xa, random_unit(g) * (0.005 * u(g)));
    ParticleInit b = particle(next++, rb, xb, random_unit(g) * (0.005 * u(g)));
    a.material = p % 3 == 1 ? 1 : 0;  // like (m, m), unlike, like (n, n) in turn
    b.material = p % 3 == 0 ? 0 : 1;
    a.angular_velocity = random_unit(g) * (400 * u(g));
    b.angular_velocity = random_unit(g) * (400 * u(g));
    scene.particles.push_back(a);
    scene.particles.push_back(b);
  }
  scene.contact_time = critical_contact_time(scene);
  scene.time_step = 0.01 * scene.contact_time;
  return scene;
}

class NewtonThirdLawTest : public testing::TestWithParam<std::tuple<Backend, int>> {
 protected:
  Case the_case() const {
    static const Case kCases[] = {
        {Backend::cpu, Precision::fp32, ContactModel::linear, kFriction | kRollingResistance | kCohesion},
        {Backend::cpu, Precision::fp64, ContactModel::hertz_mindlin, kFriction | kRollingResistance | kCohesion},
        {Backend::cpu, Precision::fp32, ContactModel::hysteretic_linear, kFriction | kRollingResistance},
    };
    Case c = kCases[std::get<1>(GetParam())];
    c.backend = std::get<0>(GetParam());
    return c;
  }
  // The snapshot after kSteps, its rows by particle id. Each sphere computes
  // its own side of its contact (GRAINSTORM_PAIRS_ONCE=0): the CPU would
  // otherwise compute the pair once and mirror it (tests/engine/test_pairs_once.cpp
  // checks that this gives these bits).
  static ParticleSnapshot run(const SceneSpec& scene, Backend backend, std::map<ParticleId, std::size_t>& row) {
    const ScopedEnv each_side("GRAINSTORM_PAIRS_ONCE", "0");
    Simulation sim(scene, RunOptions{backend});
    sim.run(kSteps);
    ParticleSnapshot s = sim.snapshot();
    for (std::size_t k = 0; k < s.size(); ++k) row[s.id[k]] = k;
    return s;
  }
};

// Random radii and materials, every effect the model takes: the forces of
// each pair are exactly opposite after kSteps (springs carried, some
// contacts sliding).
TEST_P(NewtonThirdLawTest, PairForcesAreExactlyOpposite) {
  const Case c = the_case();
  const SceneSpec scene = pairs_scene(c, false, 7);
  std::map<ParticleId, std::size_t> row;
  const ParticleSnapshot s = run(scene, c.backend, row);
  ASSERT_EQ(s.size(), scene.particles.size());
  int touching = 0;
  for (ParticleId a = 0; a < ParticleId(scene.particles.size()); a += 2) {
    const Vec3d fa = s.force[row.at(a)], fb = s.force[row.at(a + 1)];
    if (norm(fa) > 0) ++touching;
    EXPECT_EQ(fa.x, -fb.x) << "pair " << a / 2;
    EXPECT_EQ(fa.y, -fb.y) << "pair " << a / 2;
    EXPECT_EQ(fa.z, -fb.z) << "pair " << a / 2;
  }
  EXPECT_EQ(touching, kPairs + kPeriodicPairs);  // every pair still in contact: the test tests something
}

// Equal radii, friction alone: the two levers are equal, so the frictional
// torques on the two spheres are exactly the same vector.
TEST_P(NewtonThirdLawTest, EqualSpheresGetEqualFrictionTorques) {
  Case c = the_case();
  c.effects = kFriction;
  const SceneSpec scene = pairs_scene(c, true, 11);
  std::map<ParticleId, std::size_t> row;
  const ParticleSnapshot s = run(scene, c.backend, row);
  int turning = 0, sliding = 0;
  const double length = scene.domain_max.x - scene.domain_min.x;
  for (ParticleId a = 0; a < ParticleId(scene.particles.size()); a += 2) {
    const Vec3d ta = s.torque[row.at(a)], tb = s.torque[row.at(a + 1)];
    if (norm(ta) > 0) ++turning;
    EXPECT_EQ(ta.x, tb.x) << "pair " << a / 2;
    EXPECT_EQ(ta.y, tb.y) << "pair " << a / 2;
    EXPECT_EQ(ta.z, tb.z) << "pair " << a / 2;
    // At the Coulomb cap the tangential force is mu times the normal one.
    Vec3d d = s.position[row.at(a)] - s.position[row.at(a + 1)];
    if (d.x > 0.5 * length) d.x -= length;
    if (d.x < -0.5 * length) d.x += length;
    const Vec3d n = d * (1 / norm(d)), f = s.force[row.at(a)];
    const double fn = dot(f, n), ft = norm(f - n * fn);
    const double mu = a / 2 % 3 == 0 ? kSliding : a / 2 % 3 == 1 ? 0.3 : 0.4;
    if (ft > 0.999 * mu * fn) ++sliding;
  }
  EXPECT_EQ(turning, kPairs + kPeriodicPairs);
  // Both branches of the law taken: some contacts slide, the others stick.
  EXPECT_GT(sliding, 0);
  EXPECT_LT(sliding, kPairs + kPeriodicPairs);
}

std::string case_label(const testing::TestParamInfo<std::tuple<Backend, int>>& info) {
  static const char* kNames[] = {"linear_fp32", "hertz_fp64", "hysteretic_fp32"};
  return std::string(backend_name(std::get<0>(info.param))) + "_" + kNames[std::get<1>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(Backends, NewtonThirdLawTest,
                         testing::Combine(testing::ValuesIn(test_backends()), testing::Values(0, 1, 2)), case_label);

}  // namespace
}  // namespace gs::test
