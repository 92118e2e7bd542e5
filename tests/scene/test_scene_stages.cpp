// The walls' `active` windows and timed motion in scene files: what the
// loader makes of them, and its errors, each naming the key and line.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_loader.hpp"
#include "scene_test_helpers.hpp"

namespace gs {
namespace {

// Line numbers below matter: the error tests check them.
const std::string kStaged = R"(domain: {min: [-0.1, -0.1, -0.1], max: [0.1, 0.1, 0.1]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
walls:
  - {name: gate, material: glass, plane: {point: [0, 0, 0], normal: [0, 0, 1]}, active: {until: 0.5}}
  - name: floor
    material: glass
    plane: {point: [0, 0, -0.05], normal: [0, 0, 1]}
    motion:
      oscillation: {direction: [0, 0, 2], amplitude: 0.001, frequency: 20, phase: 0.5}
      velocity: {times: [0, 0.1, 0.3], values: [[0, 0, 0], [0.1, 0, 0], [0.1, 0, 0]]}
  - name: drum
    material: glass
    cylinder: {base: [0, 0, -0.09], axis: [0, 0, 1], radius: 0.09, length: 0.18}
    motion: {rotation: {axis_point: [0, 0, 0], axis: [0, 0, 1], rpm: {times: [0, 2], values: [0, 30]}}}
    active: {from: 0.2, until: 0.7}
particles:
  - list:
      - {position: [0, 0, 0.01], radius: 0.002, material: glass}
time_step: {fraction_of_contact_time: 0.1}
duration: 1
)";

std::string edit(const std::string& from, const std::string& to, const std::string& text = kStaged) {
  return test::edited(text, from, to);
}

void expect_error(const std::string& text, int line, const std::string& key, const std::string& what) {
  test::expect_scene_error(text, line, key, what);
}

TEST(SceneStages, ActiveWindowsTablesAndOscillation) {
  const SceneSpec s = parse_scene(kStaged, "s");
  ASSERT_EQ(s.walls.size(), 3u);
  ASSERT_EQ(s.wall_timelines.size(), 3u);
  EXPECT_EQ(s.wall_timelines[0].active.from, 0);
  EXPECT_EQ(s.wall_timelines[0].active.until, 0.5);
  const Timeline& floor = s.wall_timelines[1];
  EXPECT_TRUE(floor.active.always());
  EXPECT_EQ(floor.oscillation.amplitude.z, 0.001);  // along the normalised direction
  EXPECT_EQ(floor.oscillation.frequency, 20);
  EXPECT_EQ(floor.oscillation.phase, 0.5);
  ASSERT_EQ(floor.velocity.time.size(), 3u);
  EXPECT_EQ(floor.velocity.value[1].x, 0.1);
  EXPECT_DOUBLE_EQ(floor.velocity.integral[2].x, 0.025);  // 0.1 * 0.1 / 2 + 0.1 * 0.2
  const Timeline& drum = s.wall_timelines[2];
  EXPECT_EQ(drum.active.from, 0.2);
  EXPECT_EQ(drum.active.until, 0.7);
  EXPECT_NEAR(drum.angular_velocity.value[1].z, M_PI, 1e-15);  // 30 rpm = pi rad/s
  EXPECT_EQ(norm2(s.walls[2].angular_velocity), 0.0) << "the table replaces the constant rate";
  // rad/s instead of rpm.
  const SceneSpec r = parse_scene(edit("rpm: {times: [0, 2], values: [0, 30]}", "angular_speed: 2"), "s");
  EXPECT_EQ(r.walls[2].angular_velocity.z, 2.0);
}

TEST(SceneStages, ErrorsNameTheKey) {
  expect_error(edit("active: {until: 0.5}", "active: {from: 0.6, until: 0.5}"), 8, "walls[0].active.until",
               "must be after `from`");
  expect_error(edit("times: [0, 0.1, 0.3]", "times: [0, 0.3, 0.1]"), 14, "walls[1].motion.velocity.times[2]",
               "times must increase strictly");
  expect_error(edit("times: [0, 0.1, 0.3]", "times: [0.1, 0.2, 0.3]"), 14, "walls[1].motion.velocity.times[0]",
               "the first time must be 0");
  expect_error(edit("times: [0, 0.1, 0.3]", "times: [0, 0.1]"), 14, "walls[1].motion.velocity.values",
               "3 values for 2 times");
  expect_error(edit("amplitude: 0.001", "amplitude: 0"), 13, "walls[1].motion.oscillation.amplitude", "");
  expect_error(edit("frequency: 20", "frequency: -1"), 13, "walls[1].motion.oscillation.frequency", "");
  expect_error(edit("rpm: {times: [0, 2], values: [0, 30]}", "rpm: 3, angular_speed: 2"), 18, "walls[2].motion.rotation",
               "");
}

// Line numbers below matter: the error tests check them.
const std::string kSheets = R"(domain: {min: [-0.1, -0.1, -0.3], max: [0.1, 0.1, 0.3]}
gravity: [0, 0, -9.81]
materials:
  - {name: steel, density: 7800}
pairs:
  - {materials: [steel, steel], stiffness_normal: 1000, restitution: 0.5}
walls:
  - {name: bottom, material: steel, plate: {point: [0, 0, 0], normal: [0, 0, 2], radius: 0.05, hole: {radius: 0.01}}}
  - {name: slot, material: steel, plate: {point: [0, 0, 0.1], normal: [0, 0, 1], hole: {lengths: [0.04, 0.02], along: [1, 1, 0]}}}
  - {name: hopper, material: steel, cone: {base: [0, 0, -0.2], axis: [0, 0, 1], length: 0.1, base_radius: 0.01, half_angle: 30}}
particles:
  - list:
      - {position: [0.03, 0, 0.01], radius: 0.002, material: steel}
time_step: {fraction_of_contact_time: 0.1}
duration: 1
)";

TEST(SceneStages, PlatesAndCones) {
  const SceneSpec s = parse_scene(kSheets, "s");
  ASSERT_EQ(s.walls.size(), 3u);
  EXPECT_EQ(s.walls[0].kind, WallKind::plate);
  EXPECT_EQ(s.walls[0].normal.z, 1.0);
  EXPECT_EQ(s.walls[0].radius, 0.05);
  EXPECT_EQ(s.walls[0].hole_half[0], 0.01);
  EXPECT_EQ(s.walls[0].hole_half[1], 0.0);
  EXPECT_TRUE(std::isinf(s.walls[1].radius));
  EXPECT_EQ(s.walls[1].hole_half[0], 0.02);
  EXPECT_EQ(s.walls[1].hole_half[1], 0.01);
  EXPECT_NEAR(s.walls[1].tangent.x, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(s.walls[2].kind, WallKind::cone);
  EXPECT_NEAR(s.walls[2].end_radius, 0.01 + 0.1 * std::tan(M_PI / 6), 1e-15);
  // A particle cutting into the plate from below is refused as from above.
  EXPECT_THROW(parse_scene(edit("[0.03, 0, 0.01]", "[0.03, 0, -0.001]", kSheets), "s"), SceneError);
  // Over the hole, it is not.
  EXPECT_NO_THROW(parse_scene(edit("[0.03, 0, 0.01]", "[0.0, 0, 0.0]", kSheets), "s"));
}

TEST(SceneStages, SheetErrorsNameTheKey) {
  expect_error(edit("hole: {radius: 0.01}", "hole: {radius: 0.06}", kSheets), 8, "walls[0].plate.hole.radius",
               "does not fit in the plate");
  expect_error(edit("radius: 0.05, hole: {radius: 0.01}", "radius: 0.02, hole: {lengths: [0.04, 0.02], along: [1, 0, 0]}",
                    kSheets),
               8, "walls[0].plate.hole.lengths", "does not fit in the plate");
  expect_error(edit("along: [1, 1, 0]", "along: [0, 0, 3]", kSheets), 9, "walls[1].plate.hole.along",
               "must not be along the plate's normal");
  expect_error(edit("half_angle: 30", "half_angle: 0", kSheets), 10, "walls[2].cone.half_angle", "(0, 90)");
  expect_error(edit("half_angle: 30", "half_angle: 90", kSheets), 10, "walls[2].cone.half_angle", "(0, 90)");
  expect_error(edit("length: 0.1,", "length: 0,", kSheets), 10, "walls[2].cone.length", "");
  expect_error(edit("base_radius: 0.01", "base_radius: -0.01", kSheets), 10, "walls[2].cone.base_radius", "");
}

// A particle where a wall will only be later is no overlap at t = 0.
TEST(SceneStages, WallsNotYetActiveDoNotBlockThePacking) {
  const std::string inside_lid = edit("{position: [0, 0, 0.01]", "{position: [0, 0, 0.0005]");
  EXPECT_THROW(parse_scene(inside_lid, "s"), SceneError);
  EXPECT_NO_THROW(parse_scene(edit("active: {until: 0.5}", "active: {from: 0.1}", inside_lid), "s"));
}

}  // namespace
}  // namespace gs
