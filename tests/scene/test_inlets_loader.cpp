// The `inlets:` section (docs/SCENES.md): what it produces, and each bad
// inlet refused with the file, line and key.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/particle_sources.hpp"
#include "scene/scene_loader.hpp"
#include "scene_test_helpers.hpp"

namespace gs {
namespace {

// Line numbers below matter: the error tests check them. Starts empty.
const std::string kSilo = R"(domain: {min: [-0.05, -0.05, 0], max: [0.05, 0.05, 0.2]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
inlets:
  - name: feed
    material: glass
    region: {cylinder: {base: [0, 0, 0.15], axis: [0, 0, 1], radius: 0.04, length: 0.02}}
    diameter_distribution: [{diameter: 0.002, fraction: 0.5}, {diameter: 0.004, fraction: 0.5}]
    fractions_by: mass
    rate: {mass: 0.5}
    total: {mass: 2}
    start: 0.1
    stop: 3
    interval: 0.002
    velocity: [0, 0, -1]
    velocity_spread: 0.1
    seed: 9
time_step: {fraction_of_contact_time: 0.1}
duration: 5
)";

std::string edit(const std::string& from, const std::string& to, const std::string& text = kSilo) {
  return test::edited(text, from, to);
}

void expect_error(const std::string& text, int line, const std::string& key, const std::string& what) {
  test::expect_scene_error(text, line, key, what, "silo.yaml");
}

TEST(InletsLoader, SiloInletParses) {
  const SceneSpec s = parse_scene(kSilo, "silo.yaml");
  EXPECT_EQ(particle_count(s), 0u);  // an empty silo
  ASSERT_EQ(s.inlets.size(), 1u);
  const InletSpec& in = s.inlets[0];
  EXPECT_EQ(in.name, "feed");
  EXPECT_EQ(in.key, "silo.yaml:8: inlets[0]");
  EXPECT_EQ(in.region.kind, FillRegion::Kind::cylinder);
  EXPECT_EQ(in.rate_of, InletSpec::Amount::mass);
  EXPECT_EQ(in.rate, 0.5);
  EXPECT_EQ(in.total_of, InletSpec::Amount::mass);
  EXPECT_EQ(in.total, 2);
  EXPECT_EQ(in.start, 0.1);
  EXPECT_EQ(in.stop, 3);
  EXPECT_EQ(in.velocity_spread, 0.1);
  EXPECT_EQ(in.tmpl.velocity.z, -1);
  EXPECT_EQ(in.seed, 9u);
  EXPECT_EQ(in.interval_steps, std::llround(0.002 / s.time_step));
  // Equal masses of 2 and 4 mm spheres: 8 small ones per large one by count.
  ASSERT_EQ(in.size.classes.size(), 2u);
  EXPECT_NEAR(in.size.classes[0].fraction, 8.0 / 9.0, 1e-15);
  // The inlet's sizes set the contact search and the time step.
  EXPECT_EQ(largest_radius(s), 0.002);
  EXPECT_EQ(smallest_radius(s), 0.001);
}

TEST(InletsLoader, EmptyParticleListWithInlets) {
  const SceneSpec s = parse_scene(edit("inlets:", "particles: []\ninlets:"), "silo.yaml");
  EXPECT_EQ(particle_count(s), 0u);
  EXPECT_EQ(s.inlets.size(), 1u);
}

TEST(InletsLoader, RegionOutsideTheDomain) {
  expect_error(edit("radius: 0.04, length", "radius: 0.06, length"), 10, "inlets[0].region",
               "is not inside the domain");
}

TEST(InletsLoader, SizesThatDoNotFit) {
  expect_error(edit("length: 0.02}}", "length: 0.003}}"), 11, "inlets[0].diameter_distribution",
               "does not fit in the inlet region");
}

TEST(InletsLoader, RateThatCannotBePlaced) {
  expect_error(edit("rate: {mass: 0.5}", "rate: {mass: 50}"), 13, "inlets[0].rate", "cannot be placed");
}

TEST(InletsLoader, NeitherRateNorTotal) {
  std::string text = edit("    rate: {mass: 0.5}\n", "");
  expect_error(edit("    total: {mass: 2}\n", "", text), 8, "inlets[0]", "needs a rate, a total, or both");
}

TEST(InletsLoader, RateOfCountOrMassOnly) {
  expect_error(edit("rate: {mass: 0.5}", "rate: {volume: 0.5}"), 13, "inlets[0].rate.volume", "unknown key");
  expect_error(edit("rate: {mass: 0.5}", "rate: {mass: -1}"), 13, "inlets[0].rate.mass", "");
}

TEST(InletsLoader, StopBeforeStart) {
  expect_error(edit("stop: 3", "stop: 0.05"), 16, "inlets[0].stop", "must lie after start");
}

TEST(InletsLoader, StartAfterTheRun) {
  expect_error(edit("start: 0.1", "start: 7"), 15, "inlets[0].start", "before the end of the run");
}

TEST(InletsLoader, FractionsByWithoutDistribution) {
  std::string text = edit(
      "    diameter_distribution: [{diameter: 0.002, fraction: 0.5}, {diameter: 0.004, fraction: 0.5}]\n",
      "    radius: 0.001\n");
  expect_error(text, 12, "inlets[0].fractions_by", "applies to a diameter_distribution only");
}

TEST(InletsLoader, UnknownMaterialAndKey) {
  expect_error(edit("material: glass", "material: sand"), 9, "inlets[0].material", "sand");
  expect_error(edit("seed: 9", "sed: 9"), 20, "inlets[0].sed", "unknown key");
}

TEST(InletsLoader, NameUsedTwice) {
  const std::string second = "  - {name: feed, material: glass, radius: 0.001, total: {count: 10},\n"
                             "     region: {box: {min: [0, 0, 0.01], max: [0.01, 0.01, 0.02]}}}\n";
  expect_error(edit("time_step:", second + "time_step:"), 21, "inlets[1]", "used twice");
}

TEST(InletsLoader, EmptySceneWithoutInletsIsStillRefused) {
  std::string text = edit("inlets:", "particles: []\nx_inlets:");
  const std::size_t at = text.find("x_inlets:");
  text = text.substr(0, at) + "time_step: {fraction_of_contact_time: 0.1}\nduration: 5\n";
  expect_error(text, 7, "particles", "the scene has no particles");
}

}  // namespace
}  // namespace gs
