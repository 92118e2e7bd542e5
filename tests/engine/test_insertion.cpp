// Insertion through inlets (engine/insertion.hpp): the count and mass
// inserted against the requested rate, no overlap after insertion (every
// pair checked directly), the size distribution by mass fraction, and a
// restart in the middle of a fill against the uninterrupted run. On every
// backend the suite runs on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "engine/insertion.hpp"
#include "io/checkpoint.hpp"
#include "scene/generators.hpp"
#include "walls/triangle_mesh.hpp"
#include "io/restart.hpp"
#include "scene/scene_loader.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// An open box [-0.01, 0.01]^2 x [-0.02, 0.02] with a floor at z = -0.02, an
// inlet box in its upper part feeding spheres of 0.5 to 0.8 mm.
SceneSpec box_with_inlet(double gravity) {
  SceneSpec s = base_scene(2500, 2000, 0.5, 0.5);
  s.effects = kFriction;
  s.gravity = {0, 0, -gravity};
  s.walls = {plane_wall({0, 0, -0.02}, {0, 0, 1}), plane_wall({-0.01, 0, 0}, {1, 0, 0}),
             plane_wall({0.01, 0, 0}, {-1, 0, 0}), plane_wall({0, -0.01, 0}, {0, 1, 0}),
             plane_wall({0, 0.01, 0}, {0, -1, 0})};
  InletSpec in;
  in.name = "feed";
  in.region.min = {-0.01, -0.01, 0.0};
  in.region.max = {0.01, 0.01, 0.01};
  in.size.kind = SizeSpec::Kind::uniform;
  in.size.radius_min = 0.0005;
  in.size.radius_max = 0.0008;
  in.rate = 20000;  // per second
  in.interval_steps = 10;
  in.velocity_spread = 0.05;
  in.tmpl.velocity = {0, 0, -0.2};
  in.seed = 11;
  s.inlets.push_back(in);
  s.time_step = 1e-5;
  return s;
}

// Every pair of spheres, directly: the deepest overlap relative to the sum of radii (<= 0: none).
double deepest_overlap(const ParticleSnapshot& s) {
  double worst = -1;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const double sum = double(s.radius[i]) + double(s.radius[j]);
      worst = std::max(worst, (sum - norm(s.position[i] - s.position[j])) / sum);
    }
  return worst;
}

class Insertion : public ::testing::TestWithParam<Backend> {
 protected:
  RunOptions options() const {
    RunOptions o;
    o.backend = GetParam();
    return o;
  }
};

// A count rate is met exactly at every batch: floor(rate * t) particles, ids
// 0, 1, ... in order, nothing placed twice.
TEST_P(Insertion, CountRateIsExactAtEveryBatch) {
  const SceneSpec s = box_with_inlet(9.81);
  Simulation sim(s, options());
  for (int batch = 1; batch <= 30; ++batch) {
    sim.run(10);
    const ParticleSnapshot snap = sim.snapshot();
    const std::size_t due = std::size_t(std::floor(20000 * sim.time() * (1 + 1e-12)));
    ASSERT_EQ(snap.size(), due) << "at t = " << sim.time();
    for (std::size_t i = 0; i < snap.size(); ++i) ASSERT_EQ(snap.id[i], ParticleId(i));
    EXPECT_EQ(sim.insertion().next_id, due);
    EXPECT_EQ(sim.insertion().inlets[0].inserted, due);
  }
}

// Start and stop bound the time that owes particles: floor(rate * (min(t,
// stop) - start)) in all. Each new particle leaves with the inlet's velocity
// plus a spread uniform in [-0.05, 0.05] per component.
TEST_P(Insertion, StartStopAndVelocitySpread) {
  SceneSpec s = box_with_inlet(0);
  s.inlets[0].start = 0.0005;
  s.inlets[0].stop = 0.0017;
  Simulation sim(s, options());
  double spread_seen = 0;
  for (int batch = 1; batch <= 25; ++batch) {
    sim.run(10);
    const ParticleSnapshot snap = sim.snapshot();
    const double owed_time = std::max(0.0, std::min(sim.time(), 0.0017) - 0.0005);
    ASSERT_EQ(snap.size(), std::size_t(std::floor(20000 * owed_time * (1 + 1e-12)))) << "at t = " << sim.time();
    for (std::size_t i = 0; i < snap.size(); ++i) {
      const Vec3d dv = snap.velocity[i] - Vec3d(0, 0, -0.2);
      for (double c : {dv.x, dv.y, dv.z}) {
        ASSERT_LE(std::abs(c), 0.05);
        spread_seen = std::max(spread_seen, std::abs(c));
      }
    }
  }
  EXPECT_EQ(sim.snapshot().size(), 24u);  // 20000 / s for 1.2 ms
  EXPECT_GT(spread_seen, 0.04);
}

// A mass rate: the inserted mass reaches rate * t and passes it by less than
// one particle; the mass recorded equals the particles' stored masses.
TEST_P(Insertion, MassRateWithinOneParticle) {
  SceneSpec s = box_with_inlet(9.81);
  s.inlets[0].rate_of = InletSpec::Amount::mass;
  s.inlets[0].rate = 0.03;  // kg/s: some 10 particles per batch
  Simulation sim(s, options());
  const double largest = stored_sphere_mass(0.0008, 2500);
  for (int batch = 1; batch <= 20; ++batch) {
    sim.run(10);
    const ParticleSnapshot snap = sim.snapshot();
    double mass = 0;
    for (float m : snap.mass) mass += double(m);
    const double due = 0.03 * sim.time();
    EXPECT_GE(mass, due);
    EXPECT_LT(mass, due + largest);
    EXPECT_EQ(mass, sim.insertion().inlets[0].mass);
  }
}

// A total stops the inlet: a count total of 123 at a rate that would give more.
TEST_P(Insertion, TotalStopsTheInlet) {
  SceneSpec s = box_with_inlet(9.81);
  s.inlets[0].total = 123;
  Simulation sim(s, options());
  sim.run(1000);  // 200 due by the rate
  EXPECT_EQ(sim.snapshot().size(), 123u);
  EXPECT_EQ(sim.insertion().inlets[0].inserted, 123u);
}

// Without a rate the whole total is owed at once: a count total at the first
// batch, a mass total by less than one particle beyond it.
TEST_P(Insertion, TotalWithoutRateAtFirstBatch) {
  SceneSpec s = box_with_inlet(9.81);
  s.inlets[0].rate = 0;
  s.inlets[0].total = 40;
  Simulation by_count(s, options());
  by_count.run(10);
  EXPECT_EQ(by_count.snapshot().size(), 40u);
  s.inlets[0].total_of = InletSpec::Amount::mass;
  s.inlets[0].total = 0.0001;  // kg: some 40 particles
  Simulation by_mass(s, options());
  by_mass.run(10);
  const double mass = by_mass.insertion().inlets[0].mass;
  EXPECT_GE(mass, 0.0001);
  EXPECT_LT(mass, 0.0001 + stored_sphere_mass(0.0008, 2500));
  by_mass.run(100);
  EXPECT_EQ(by_mass.insertion().inlets[0].mass, mass) << "the total is reached: nothing more";
}

// Inserted particles overlap nothing: not the particles already there (a
// lattice at rest inside the inlet region, no gravity), not each other, not
// the walls. Checked right after each batch over every pair.
TEST_P(Insertion, NoOverlapWithParticlesWallsOrEachOther) {
  SceneSpec s = box_with_inlet(0);
  s.inlets[0].tmpl.velocity = {};
  s.inlets[0].velocity_spread = 0;
  s.inlets[0].rate = 200000;  // dense: each batch of 20 competes for room
  s.inlets[0].interval_steps = 5;
  s.walls.push_back(plane_wall({0, 0, 0.004}, {0, 0, -1}));  // cuts the inlet region: candidates above it must fail
  LatticeSpec l;
  l.radius = 0.0007;
  l.spacing = 0.0025;
  l.min = {-0.009, -0.009, 0.0008};
  l.max = {0.009, 0.009, 0.0032};
  generate_lattice(l, s.particles);
  const std::size_t existing = s.particles.size();
  Simulation sim(s, options());
  std::uint64_t shortfall = 0;
  for (int batch = 1; batch <= 12; ++batch) {
    sim.run(5);
    for (const InsertionRecord& r : sim.take_insertion_records()) shortfall += r.shortfall;
    const ParticleSnapshot snap = sim.snapshot();
    ASSERT_GT(snap.size(), existing);
    EXPECT_LE(deepest_overlap(snap), 1e-9) << "after batch " << batch;
    for (std::size_t i = 0; i < snap.size(); ++i)
      for (const Wall& w : s.walls) ASSERT_LE(wall_penetration(w, snap.position[i], snap.radius[i]), 1e-12);
  }
  EXPECT_GT(sim.snapshot().size(), existing + 50);
  EXPECT_GT(shortfall, 0u) << "the test needs batches that cannot place everything";
}

// A mesh plate rising through the inlet region at 2 m/s: each batch's new
// particles keep clear of the plate where it is at that step (|z - z_plate|
// >= r), not where it started.
TEST_P(Insertion, MeshesAreAvoidedInTheirCurrentPose) {
  SceneSpec s = box_with_inlet(0);
  s.inlets[0].tmpl.velocity = {};
  s.inlets[0].velocity_spread = 0;
  s.inlets[0].rate = 200000;
  s.inlets[0].interval_steps = 5;
  TriangleMeshBuilder plate("plate");
  const double z0 = 0.002;
  plate.quad(plate.vertex({-0.02, -0.02, z0}), plate.vertex({0.02, -0.02, z0}), plate.vertex({0.02, 0.02, z0}),
             plate.vertex({-0.02, 0.02, z0}));
  MeshMotion rising;
  rising.velocity = {0, 0, 2};
  add_mesh(s.meshes, plate.take(), 0, rising);
  Simulation sim(s, options());
  std::size_t before = 0;
  for (int batch = 1; batch <= 12; ++batch) {
    sim.run(5);
    const ParticleSnapshot snap = sim.snapshot();
    const double z_plate = z0 + 2 * sim.time();
    for (std::size_t i = before; i < snap.size(); ++i)
      ASSERT_GE(std::abs(snap.position[i].z - z_plate), double(snap.radius[i])) << "batch " << batch;
    before = snap.size();
  }
  EXPECT_GT(before, 100u);
}

// A restart from a checkpoint written mid-fill continues the same insertion:
// same ids, same positions, bit for bit, and the same inlet state.
TEST_P(Insertion, RestartMidFillMatchesUninterruptedRun) {
  const SceneSpec s = box_with_inlet(9.81);
  Simulation whole(s, options());
  whole.run(400);
  Simulation first(s, options());
  first.run(205);  // between batches: the next is at step 210
  const std::string path = (std::filesystem::path(::testing::TempDir()) / "insertion_restart.h5").string();
  write_checkpoint(path, make_checkpoint(first.snapshot(), first.history(), first.walls(), 0, 1, first.insertion()));
  Simulation second(s, options(), nullptr, restart_state(read_checkpoint(path)));
  second.run(195);
  const ParticleSnapshot a = whole.snapshot(), b = second.snapshot();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(same_bits(a.id, b.id));
  EXPECT_TRUE(same_bits(a.position, b.position));
  EXPECT_TRUE(same_bits(a.velocity, b.velocity));
  EXPECT_TRUE(same_bits(a.angular_velocity, b.angular_velocity));
  EXPECT_EQ(whole.insertion().next_id, second.insertion().next_id);
  EXPECT_EQ(whole.insertion().inlets[0].mass, second.insertion().inlets[0].mass);
  EXPECT_EQ(whole.insertion().inlets[0].batches, second.insertion().inlets[0].batches);
  std::filesystem::remove(path);
}

INSTANTIATE_TEST_SUITE_P(Backends, Insertion, ::testing::ValuesIn(test_backends()), backend_label);

// Sizes by mass fraction (the loader converts them to count fractions): 30 %
// of the mass in 1 mm spheres, 70 % in 2 mm. The count of 1 mm spheres among
// n is binomial with p = (0.3 / 1) / (0.3 / 1 + 0.7 / 8) = 0.774; its 4-sigma
// range, carried over to the mass fraction, bounds the measured one.
TEST(InsertionSizes, MassFractionsMatchWithinFourSigma) {
  const std::string scene = R"(domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}
materials: [{name: glass, density: 2500}]
pairs: [{materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}]
inlets:
  - material: glass
    region: {box: {min: [0.01, 0.01, 0.01], max: [0.09, 0.09, 0.09]}}
    diameter_distribution: [{diameter: 0.001, fraction: 0.3}, {diameter: 0.002, fraction: 0.7}]
    fractions_by: mass
    total: {count: 20000}
time_step: {fraction_of_contact_time: 0.1}
duration: 1
)";
  const SceneSpec s = parse_scene(scene, "mass_fractions.yaml");
  const InletBatch b = inlet_batch(s.inlets[0], 0, InletState{}, 0.0, s.materials);
  ASSERT_EQ(b.pending.size(), 20000u);
  double small_mass = 0, mass = 0;
  std::size_t small = 0;
  for (std::size_t k = 0; k < b.pending.size(); ++k) {
    mass += double(b.mass[k]);
    if (b.pending[k].radius < 0.00075) {
      small_mass += double(b.mass[k]);
      ++small;
    }
  }
  const double n = 20000, p = (0.3 / 1) / (0.3 / 1 + 0.7 / 8), sigma = std::sqrt(n * p * (1 - p));
  auto mass_fraction = [&](double n_small) { return n_small / (n_small + 8 * (n - n_small)); };
  EXPECT_NEAR(double(small), n * p, 4 * sigma);
  EXPECT_GT(small_mass / mass, mass_fraction(n * p - 4 * sigma));
  EXPECT_LT(small_mass / mass, mass_fraction(n * p + 4 * sigma));
  EXPECT_NEAR(mass_fraction(n * p), 0.3, 1e-12);  // the conversion itself
}

}  // namespace
}  // namespace gs::test
