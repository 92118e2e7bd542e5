// Each touching pair computed once for both spheres (the CPU's force
// computation: engine/force_kernel.hpp, pairs_of and sum_entries): the
// partner's load and springs are taken mirrored from the sphere that
// computed the law, and must have the bits the partner's own computation
// gives (GRAINSTORM_PAIRS_ONCE=0, as the GPU computes). A dense, jostling
// bed of unequal spheres of two materials between walls, wrapping along x,
// under gravity, over a quiet lattice settling from rest; every effect the
// model takes: the state after a few hundred steps, history included, bit
// for bit the same either way. It fails when the partner's torque takes the
// computing sphere's lever, when its springs are not mirrored, and (the
// Hertz case) when the springs' zeros are stored as they come: the quiet
// lattice's springs have exact zeros, +0 from one side, -0 mirrored.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <string>

#include "backend/backend.hpp"
#include "engine/pairs_once_policy.hpp"
#include "io/state_digest.hpp"
#include "scene/scene_time_step.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr const char* kVariable = "GRAINSTORM_PAIRS_ONCE";
constexpr int kSide = 6, kLayers = 9, kQuietLayers = 3, kSteps = 300;
constexpr double kSpacing = 0.002;  // between lattice sites: spheres of 0.99-1.02 mm partly touch

// Each test sets GRAINSTORM_PAIRS_ONCE as it needs; it is put back after.
class PairsOnceTest : public testing::TestWithParam<int> {
 protected:
  ScopedEnv env_{kVariable, nullptr};
};

struct Case {
  Precision precision;
  ContactModel model;
  unsigned effects;
};
constexpr Case kCases[] = {
    {Precision::fp32, ContactModel::linear, kFriction | kRollingResistance | kCohesion},
    {Precision::fp64, ContactModel::hertz_mindlin, kFriction | kRollingResistance},
    {Precision::fp32, ContactModel::hysteretic_linear, kFriction},
    {Precision::fp32, ContactModel::linear, 0},
};

// A kSide x kSide x kLayers lattice of spheres of two materials on a floor,
// between walls along y, wrapping along x. The kQuietLayers at the bottom:
// equal spheres pressed 0.1 % into their neighbours, at rest, settling
// straight down (their springs have exact zeros across the lattice's axes);
// above a gap of one layer, spheres of random radii 0.99-1.02 mm (some
// sites overlap their neighbours, some do not), half at rest, half moving
// and spinning at random.
SceneSpec bed(const Case& c) {
  SceneSpec scene = base_scene(2500, 1000, 0.5, 0.5, c.model);
  scene.precision = c.precision;
  scene.effects = c.effects;
  scene.pairs[0].rolling_friction = 0.1;
  scene.pairs[0].cohesion_energy_density = 2e3;
  add_second_material(scene);
  scene.domain_min = {0, 0, 0};
  scene.domain_max = {kSide * kSpacing, kSide * kSpacing, 2 * kLayers * kSpacing};
  scene.periodic_axes = 1u;  // x
  scene.gravity = {0, 0, -9.81};
  scene.walls.push_back(plane_wall({0, 0, 0}, {0, 0, 1}));
  scene.walls.push_back(plane_wall({0, 0, 0}, {0, 1, 0}));
  scene.walls.push_back(plane_wall({0, kSide * kSpacing, 0}, {0, -1, 0}, 0));
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(-1, 1);
  ParticleId next = 0;
  for (int z = 0; z < kLayers; ++z)
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        if (z == kQuietLayers) continue;  // the gap: the jostling layers fall for longer than the run
        const bool quiet = z < kQuietLayers;
        const Vec3d at{(x + 0.5) * kSpacing, (y + 0.5) * kSpacing, (z + 0.5) * kSpacing};
        ParticleInit p = particle(next, quiet ? 0.001001 : 0.001 * (1.005 + 0.015 * u(g)), at);
        p.material = next % 3 == 0 ? 1 : 0;
        if (!quiet && next % 2 == 1) {
          p.velocity = Vec3d{u(g), u(g), u(g)} * 0.01;
          p.angular_velocity = Vec3d{u(g), u(g), u(g)} * 200.0;
        }
        scene.particles.push_back(p);
        ++next;
      }
  scene.contact_time = critical_contact_time(scene);
  scene.time_step = 0.02 * scene.contact_time;
  return scene;
}

struct Outcome {
  std::uint64_t digest;
  ParticleSnapshot snapshot;
};

Outcome run(const SceneSpec& scene, const char* pairs_once) {
  const ScopedEnv setting(kVariable, pairs_once);
  Simulation sim(scene, RunOptions{Backend::cpu});
  sim.run(kSteps);
  const ParticleSnapshot s = sim.snapshot();
  return {state_digest(s, sim.history()), s};
}

TEST_P(PairsOnceTest, GivesTheBitsOfEachSphereComputingItsOwnSide) {
  const Case c = kCases[GetParam()];
  const SceneSpec scene = bed(c);
  const Outcome once = run(scene, "1"), each = run(scene, "0"), chosen = run(scene, "auto");
  std::printf("pairs once 0x%016" PRIx64 ", each side 0x%016" PRIx64 ", chosen 0x%016" PRIx64 "\n", once.digest,
              each.digest, chosen.digest);
  EXPECT_EQ(chosen.digest, once.digest);
  ASSERT_EQ(once.snapshot.size(), each.snapshot.size());
  int moving = 0;
  for (std::size_t r = 0; r < once.snapshot.size(); ++r) {
    const Vec3d f1 = once.snapshot.force[r], f0 = each.snapshot.force[r];
    const Vec3d t1 = once.snapshot.torque[r], t0 = each.snapshot.torque[r];
    ASSERT_TRUE(f1.x == f0.x && f1.y == f0.y && f1.z == f0.z) << "force of particle " << once.snapshot.id[r];
    ASSERT_TRUE(t1.x == t0.x && t1.y == t0.y && t1.z == t0.z) << "torque of particle " << once.snapshot.id[r];
    if (norm(once.snapshot.velocity[r]) > 1e-3) ++moving;
  }
  EXPECT_EQ(once.digest, each.digest) << "the state's bits (history included)";
  EXPECT_GT(moving, 10);  // still jostling: the contacts are live, not a bed at rest
}

std::string case_label(const testing::TestParamInfo<int>& info) {
  static const char* kNames[] = {"linear_fp32_all", "hertz_fp64", "hysteretic_fp32", "linear_frictionless"};
  return kNames[info.param];
}

INSTANTIATE_TEST_SUITE_P(Models, PairsOnceTest, testing::Values(0, 1, 2, 3), case_label);

// The automatic choice: each pair once from the start; each side from a
// step counted below kFrom touching entries per particle, until kRetryEvery
// steps later; once again from a count at or above it.
TEST(PairsOncePolicy, ChoosesOncePerPairWhereMostEntriesTouch) {
  PairsOncePolicy p(PairsOnceSetting::automatic);
  EXPECT_TRUE(p.choose(0));
  p.counted(PairsOncePolicy::kFrom, 0);
  EXPECT_TRUE(p.choose(1));
  p.counted(0.5 * PairsOncePolicy::kFrom, 1);
  EXPECT_FALSE(p.choose(2));
  EXPECT_FALSE(p.choose(PairsOncePolicy::kRetryEvery));
  EXPECT_TRUE(p.choose(1 + PairsOncePolicy::kRetryEvery));
  p.counted(0.9 * PairsOncePolicy::kFrom, 1 + PairsOncePolicy::kRetryEvery);
  EXPECT_FALSE(p.choose(2 + PairsOncePolicy::kRetryEvery));
  EXPECT_TRUE(p.choose(1 + 2 * PairsOncePolicy::kRetryEvery));
  p.counted(3 * PairsOncePolicy::kFrom, 1 + 2 * PairsOncePolicy::kRetryEvery);
  EXPECT_TRUE(p.choose(2 + 2 * PairsOncePolicy::kRetryEvery));
  EXPECT_TRUE(p.counts());
  // Set by hand, the count changes nothing (and is not asked for).
  PairsOncePolicy always(PairsOnceSetting::always), never(PairsOnceSetting::never);
  EXPECT_FALSE(always.counts());
  EXPECT_FALSE(never.counts());
  always.counted(0, 0);
  never.counted(100, 0);
  EXPECT_TRUE(always.choose(1));
  EXPECT_FALSE(never.choose(0));
  EXPECT_FALSE(never.choose(1000));
}

TEST(PairsOnceSetting, UnknownValueIsRefusedByName) {
  const ScopedEnv env(kVariable, nullptr);
  for (const char* bad : {"2", "yes", "on", "1 ", "automatic"}) {
    env.set(bad);
    try {
      pairs_once_setting();
      ADD_FAILURE() << bad << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(kVariable), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
  env.set("0");
  EXPECT_EQ(pairs_once_setting(), PairsOnceSetting::never);
  env.set("1");
  EXPECT_EQ(pairs_once_setting(), PairsOnceSetting::always);
  env.set("auto");
  EXPECT_EQ(pairs_once_setting(), PairsOnceSetting::automatic);
  env.set(nullptr);
  EXPECT_EQ(pairs_once_setting(), PairsOnceSetting::automatic);
}

}  // namespace
}  // namespace gs::test
