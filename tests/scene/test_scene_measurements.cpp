// The `measurements:` section (docs/SCENES.md): what it gives, and every bad
// value refused with the file, line and key.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_loader.hpp"
#include "scene_test_helpers.hpp"

namespace gs {
namespace {

// Line numbers below matter: the error tests check them (the measurements start on line 13).
const std::string kScene = R"(domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
particles:
  - lattice: {material: glass, radius: 0.001, min: [0.01, 0.01, 0.01], max: [0.019, 0.029, 0.039], spacing: 0.003}
time_step: {fraction_of_contact_time: 0.1}
duration: 0.5
output: {interval: 0.01, directory: res}
measurements:
  flows:
    - {name: outlet, plane: {point: [0.05, 0.05, 0.01], normal: [0, 0, -2]}, radius: 0.02, every: 0.01, markers: [1, 3]}
    - {name: slot, plane: {point: [0.05, 0.05, 0.01], normal: [0, 0, 1]}, rectangle: {axis: [1, 0, 1], half_lengths: [0.02, 0.01]}, every: 0.02, start: 0.1}
  averages:
    - {name: bed, box: {min: [0, 0, 0], max: [0.1, 0.1, 0.05]}, bins: [1, 1, 10], quantities: [solid_fraction, stress], every: 0.05}
)";

std::string edit(const std::string& from, const std::string& to) { return test::edited(kScene, from, to); }

void expect_error(const std::string& text, int line, const std::string& key, const std::string& what) {
  test::expect_scene_error(text, line, key, what);
}

TEST(SceneMeasurements, Parses) {
  const SceneSpec s = parse_scene(kScene, "scene.yaml");
  ASSERT_EQ(s.measurements.flows.size(), 2u);
  const FlowSpec& outlet = s.measurements.flows[0];
  EXPECT_EQ(outlet.name, "outlet");
  EXPECT_EQ(outlet.normal.z, -1);  // normalised
  EXPECT_EQ(outlet.bound, FlowBound::disk);
  EXPECT_EQ(outlet.radius, 0.02);
  EXPECT_EQ(outlet.markers, (std::vector<int>{1, 3}));
  EXPECT_EQ(outlet.times.every, 0.01);
  const FlowSpec& slot = s.measurements.flows[1];
  EXPECT_EQ(slot.bound, FlowBound::rectangle);
  EXPECT_DOUBLE_EQ(slot.axis_u.x, 1);  // the axis projected into the plane
  EXPECT_DOUBLE_EQ(slot.axis_u.z, 0);
  EXPECT_DOUBLE_EQ(slot.axis_v.y, 1);  // normal x axis_u
  EXPECT_EQ(slot.half_length_u, 0.02);
  EXPECT_EQ(slot.times.start, 0.1);
  ASSERT_EQ(s.measurements.averages.size(), 1u);
  const AverageSpec& bed = s.measurements.averages[0];
  EXPECT_EQ(bed.bins, (std::array<int, 3>{1, 1, 10}));
  EXPECT_EQ(bed.quantities, (std::vector<AverageQuantity>{AverageQuantity::solid_fraction, AverageQuantity::stress}));
  EXPECT_TRUE(bed.needs_contacts());
}

TEST(SceneMeasurements, BadValuesNameTheirKey) {
  expect_error(edit("bins: [1, 1, 10]", "bins: [1, 0, 10]"), 17, "measurements.averages[0].bins[1]", "[1, 1000000]");
  expect_error(edit("bins: [1, 1, 10]", "bins: [1, 10]"), 17, "measurements.averages[0].bins", "list of 3");
  expect_error(edit("max: [0.1, 0.1, 0.05]", "max: [0.1, 0.1, 0.2]"), 17, "measurements.averages[0].box",
               "reaches outside the domain");
  expect_error(edit("max: [0.1, 0.1, 0.05]", "max: [0.1, 0.1, 0]"), 17, "measurements.averages[0].box",
               "must be below max");
  expect_error(edit("[solid_fraction, stress]", "[solid_fraction, pressure]"), 17,
               "measurements.averages[0].quantities[1]", "solid_fraction, velocity, granular_temperature");
  expect_error(edit("[solid_fraction, stress]", "[stress, stress]"), 17, "measurements.averages[0].quantities[1]",
               "listed twice");
  expect_error(edit("[solid_fraction, stress]", "[]"), 17, "measurements.averages[0].quantities", "at least one");
  expect_error(edit("name: slot", "name: outlet"), 15, "measurements.flows[1].name", "already taken");
  expect_error(edit("name: slot", "name: a/b"), 15, "measurements.flows[1].name", "letters, digits");
  expect_error(edit("point: [0.05, 0.05, 0.01], normal: [0, 0, -2]", "point: [0.05, 0.05, 0.2], normal: [0, 0, -2]"), 14,
               "measurements.flows[0].plane.point", "outside the domain");
  expect_error(edit("normal: [0, 0, -2]", "normal: [0, 0, 0]"), 14, "measurements.flows[0].plane.normal", "zero");
  expect_error(edit("radius: 0.02,", "radius: 0.02, rectangle: {axis: [1, 0, 0], half_lengths: [1, 1]},"), 14,
               "measurements.flows[0].rectangle", "not both");
  expect_error(edit("axis: [1, 0, 1]", "axis: [0, 0, 3]"), 15, "measurements.flows[1].rectangle.axis", "parallel");
  expect_error(edit("every: 0.01,", "every: 0,"), 14, "measurements.flows[0].every", "> 0");
  expect_error(edit("every: 0.01,", "every: 1e-9,"), 14, "measurements.flows[0].every", "at least the time step");
  expect_error(edit("start: 0.1", "start: 0.7"), 15, "measurements.flows[1].start", "must not exceed the duration");
  expect_error(edit("markers: [1, 3]", "markers: [1, 1]"), 14, "measurements.flows[0].markers[1]", "twice");
  expect_error(edit("markers: [1, 3]", "markers: [256]"), 14, "measurements.flows[0].markers[0]", "[0, 255]");
  expect_error(edit("  averages:", "  average:"), 16, "measurements.average", "unknown key");
  expect_error(edit("every: 0.05}", "every: 0.05, bin: 3}"), 17, "measurements.averages[0].bin", "unknown key");
}

}  // namespace
}  // namespace gs
