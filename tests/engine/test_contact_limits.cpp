// The limits on a particle's contacts (docs/SCENES.md, contact_slots and
// surface_slots): a sphere pressed into a corner of three walls needs three
// surface slots, and a sphere among four others four contacts; one fewer
// stops the run with the fault that names the key, and exactly enough runs.
#include <gtest/gtest.h>

#include <string>

#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.001;

// A frictional sphere 0.1 mm into the walls x = 0, y = 0, z = 0.
SceneSpec corner() {
  SceneSpec scene = base_scene(2500, 1000, 0.5, 0.5);
  scene.effects = kFriction;
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {0.01, 0.01, 0.01};
  scene.walls = {plane_wall({0, 0, 0}, {1, 0, 0}), plane_wall({0, 0, 0}, {0, 1, 0}), plane_wall({0, 0, 0}, {0, 0, 1})};
  scene.particles = {particle(0, kRadius, {0.0009, 0.0009, 0.0009})};
  scene.time_step = 1e-6;
  return scene;
}

// Sphere 0 overlapped by four others along +-x and +-y, no walls.
SceneSpec cluster() {
  SceneSpec scene = base_scene(2500, 1000, 0.5, 0.5);
  scene.effects = kFriction;
  const double d = 2 * kRadius - 0.0001;
  scene.particles = {particle(0, kRadius, {0, 0, 0}), particle(1, kRadius, {d, 0, 0}), particle(2, kRadius, {-d, 0, 0}),
                     particle(3, kRadius, {0, d, 0}), particle(4, kRadius, {0, -d, 0})};
  scene.time_step = 1e-6;
  return scene;
}

// The fault's message, or "" when the run went through.
std::string fault_of(const SceneSpec& scene, Backend b) {
  try {
    Simulation sim(scene, RunOptions{b});
    sim.run(3);
  } catch (const SimulationFault& e) {
    return e.what();
  }
  return "";
}

class ContactLimitsTest : public testing::TestWithParam<Backend> {};

TEST_P(ContactLimitsTest, ACornerNeedsThreeSurfaceSlots) {
  SceneSpec scene = corner();
  scene.surface_slots = 3;
  EXPECT_EQ(fault_of(scene, GetParam()), "");
  scene.surface_slots = 2;
  EXPECT_NE(fault_of(scene, GetParam()).find("surface_slots"), std::string::npos);
}

TEST_P(ContactLimitsTest, FourNeighboursNeedFourContactSlots) {
  SceneSpec scene = cluster();
  scene.contact_slots = 4;
  EXPECT_EQ(fault_of(scene, GetParam()), "");
  scene.contact_slots = 3;
  const std::string fault = fault_of(scene, GetParam());
  EXPECT_NE(fault.find("contact_slots"), std::string::npos) << fault;
}

INSTANTIATE_TEST_SUITE_P(Backends, ContactLimitsTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
