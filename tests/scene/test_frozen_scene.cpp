// `frozen: true` on a particle set (docs/SCENES.md): which particles it
// freezes, that the run then keeps the field, and what the loader refuses.
#include <gtest/gtest.h>

#include "scene/particle_sources.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_test_helpers.hpp"

namespace gs::test {
namespace {

// A frozen lattice (ids 0-3), a random fill and a list of two (one frozen).
// Line numbers matter: the error tests check them.
const std::string kScene = R"(domain: {min: [0, 0, 0], max: [0.02, 0.02, 0.02]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
particles:
  - lattice: {material: glass, radius: 0.001, min: [0.002, 0.002, 0.002], max: [0.004, 0.004, 0.002], spacing: 0.002, frozen: true}
  - random_fill: {material: glass, region: {box: {min: [0, 0, 0.01], max: [0.02, 0.02, 0.02]}}, count: 5, radius: 0.001}
  - list:
      - {position: [0.015, 0.015, 0.002], radius: 0.001, material: glass, frozen: true}
      - {position: [0.015, 0.010, 0.002], radius: 0.001, material: glass}
time_step: {fraction_of_contact_time: 0.05}
duration: 0.1
)";

TEST(FrozenScene, MarksTheParticlesOfFrozenSets) {
  const SceneSpec s = parse_scene(kScene, "scene.yaml");
  EXPECT_TRUE(s.frozen_particles);
  EXPECT_EQ(particle_fields_kept(s) & kFrozenFlags, kFrozenFlags);
  std::vector<int> frozen(particle_count(s), -1);
  for_each_particle(s, [&](const ParticleInit& p) { frozen[p.id] = p.frozen; });
  EXPECT_EQ(frozen, std::vector<int>({1, 1, 1, 1, 0, 0, 0, 0, 0, 1, 0}));
}

TEST(FrozenScene, ARunWithoutFrozenSetsKeepsNoField) {
  const SceneSpec s = parse_scene(edited(edited(kScene, ", frozen: true}", "}"), ", frozen: true}", "}"), "s.yaml");
  EXPECT_FALSE(s.frozen_particles);
  EXPECT_EQ(particle_fields_kept(s), 0u);
  // `frozen: false` on the lattice: its particles (ids 0-3) move.
  const SceneSpec unfrozen = parse_scene(edited(kScene, "frozen: true}", "frozen: false}"), "s.yaml");
  for_each_particle(unfrozen, [&](const ParticleInit& p) {
    if (p.id < 4) {
      EXPECT_FALSE(p.frozen) << "particle " << p.id;
    }
  });
}

TEST(FrozenScene, RefusesMotionAndInlets) {
  expect_scene_error(edited(kScene, "spacing: 0.002, frozen", "velocity: [0, 0, 1], frozen"), 8,
                     "particles[0].lattice.velocity", "a frozen particle never moves");
  expect_scene_error(edited(kScene, "material: glass, frozen: true}", "material: glass, frozen: true, angular_velocity: [1, 0, 0]}"),
                     11, "angular_velocity", "a frozen particle never moves");
  expect_scene_error(edited(kScene, "frozen: true}", "frozen: maybe}"), 8, "frozen", "true or false");
  const std::string inlet = kScene + "inlets:\n  - {name: feed, material: glass, region: {box: {min: [0, 0, 0.01], "
                                     "max: [0.02, 0.02, 0.02]}}, radius: 0.001, rate: {count: 10}, frozen: true}\n";
  expect_scene_error(inlet, 16, "frozen", "");
}

}  // namespace
}  // namespace gs::test
