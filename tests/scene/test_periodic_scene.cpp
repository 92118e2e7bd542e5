// domain.periodic in the scene file: the axes, and what the loader refuses
// with it (a box too short, walls and meshes that cannot meet the periodic
// faces, particles outside the box, image counts asked of a run that keeps none).
#include <gtest/gtest.h>

#include "scene/scene_loader.hpp"

namespace gs {
namespace {

// A periodic chute cell: periodic in x and y, a plane base, gravity tilted
// by 25 degrees along x. Line numbers matter: the error tests check them.
const std::string kChute = R"(domain: {min: [0, 0, 0], max: [0.02, 0.01, 0.03], periodic: [x, y]}
gravity: [4.146, 0, -8.891]
effects: {friction: true}
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5, friction: 0.4}
walls:
  - plane: {point: [0, 0, 0], normal: [0, 0, 1]}
    material: glass
particles:
  - lattice: {material: glass, radius: 0.001, min: [0.001, 0.001, 0.0012], max: [0.019, 0.009, 0.0092], spacing: 0.002}
time_step: {fraction_of_contact_time: 0.05}
duration: 0.1
)";

std::string edit(const std::string& from, const std::string& to, std::string text = kChute) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "scene.yaml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

void expect_error(const std::string& text, int line, const std::string& key, const std::string& what) {
  const std::string msg = error_of(text);
  const std::string where = "scene.yaml:" + std::to_string(line) + ": ";
  EXPECT_EQ(msg.rfind(where, 0), 0u) << "expected " << where << " in: " << msg;
  EXPECT_NE(msg.find(key), std::string::npos) << "expected key '" << key << "' in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
}

TEST(PeriodicScene, ChuteCellLoadsWithItsAxes) {
  const SceneSpec s = parse_scene(kChute, "scene.yaml");
  EXPECT_EQ(s.periodic_axes, 3u);
  EXPECT_EQ(parse_scene(edit("periodic: [x, y]", "periodic: [y]"), "s.yaml").periodic_axes, 2u);
  EXPECT_EQ(parse_scene(edit(", periodic: [x, y]", ""), "s.yaml").periodic_axes, 0u);
}

TEST(PeriodicScene, AxesAreCheckedByName) {
  expect_error(edit("periodic: [x, y]", "periodic: [x, w]"), 1, "domain.periodic", "is not one of");
  expect_error(edit("periodic: [x, y]", "periodic: [x, x]"), 1, "domain.periodic", "listed twice");
  expect_error(edit("periodic: [x, y]", "periodic: x"), 1, "domain.periodic", "list of axes");
}

// 0.0035 m along y is less than two diameters (0.004 m): a sphere could
// touch both images of one partner.
TEST(PeriodicScene, BoxShorterThanTwoDiametersIsRefused) {
  std::string text = edit("max: [0.02, 0.01, 0.03]", "max: [0.02, 0.0035, 0.03]");
  text = edit("max: [0.019, 0.009, 0.0092]", "max: [0.019, 0.0025, 0.0092]", text);
  expect_error(text, 1, "domain.periodic", "shorter than two largest particle diameters");
  // The same box without wrapping y is fine.
  EXPECT_EQ(error_of(edit("periodic: [x, y]", "periodic: [x]", text)), "(no error)");
}

TEST(PeriodicScene, WallsThatCannotMeetThePeriodicFacesAreRefused) {
  // A plane tilted across x (an inclined base) ends at the periodic faces.
  expect_error(edit("normal: [0, 0, 1]", "normal: [-0.42, 0, 0.91]"), 9, "walls[0]",
               "only planes parallel to a periodic axis");
  // A box has faces across x and y.
  expect_error(edit("  - plane: {point: [0, 0, 0], normal: [0, 0, 1]}",
                    "  - box: {min: [0, 0, 0], max: [0.02, 0.01, 0.03]}"),
               9, "walls[0]", "cannot meet the periodic boundaries");
  // A drum along x without end caps spanning the box is fine; caps or a short one are not.
  const std::string drum = edit("periodic: [x, y]", "periodic: [x]",
                                edit("  - plane: {point: [0, 0, 0], normal: [0, 0, 1]}",
                                     "  - cylinder: {base: [0, 0.005, 0.015], axis: [1, 0, 0], radius: 0.0049, length: 0.02}"));
  const std::string drum_fits = edit("min: [0.001, 0.001, 0.0012], max: [0.019, 0.009, 0.0092]",
                                     "min: [0.001, 0.004, 0.014], max: [0.019, 0.006, 0.016]", drum);
  EXPECT_EQ(error_of(drum_fits), "(no error)");
  expect_error(edit("length: 0.02}", "length: 0.02, caps: both}", drum_fits), 9, "walls[0]", "disk");
  expect_error(edit("length: 0.02}", "length: 0.015}", drum_fits), 9, "walls[0]", "must span the domain");
  // A rotating plane turns out of the periodic axis's direction.
  expect_error(edit("    material: glass\nparticles", "    material: glass\n    motion: {rotation: {axis_point: [0, 0, 0], axis: [0, 1, 0], rpm: 1}}\nparticles"),
               9, "walls[0]", "rotates about an axis");
}

// Plates and cones are touched at the particle's own position: they must end
// inside the box along a periodic axis, a particle diameter clear of its faces.
TEST(PeriodicScene, SheetsMustKeepClearOfThePeriodicFaces) {
  auto with_wall = [](const std::string& wall) {
    return edit("    material: glass\nparticles", "    material: glass\n  - " + wall + "\n    material: glass\nparticles");
  };
  EXPECT_EQ(error_of(with_wall("plate: {point: [0.01, 0.005, 0.02], normal: [0, 0, 1], radius: 0.002}")),
            "(no error)");
  // An unbounded plate reaches the faces.
  expect_error(with_wall("plate: {point: [0.01, 0.005, 0.02], normal: [0, 0, 1]}"), 11, "walls[1]",
               "would stop at them");
  // Inside the box, but closer than a diameter (0.002 m) to x = 0.
  expect_error(with_wall("plate: {point: [0.0025, 0.005, 0.02], normal: [0, 0, 1], radius: 0.002}"), 11, "walls[1]",
               "clear of the periodic faces along x");
  // A hopper as wide as the box along y.
  expect_error(with_wall("cone: {base: [0.01, 0.005, 0.015], axis: [0, 0, 1], length: 0.01, base_radius: 0.001, "
                         "half_angle: 30}"),
               11, "walls[1]", "would stop at them");
  // A small plate that slides along x would reach them.
  expect_error(edit("    material: glass\nparticles",
                    "    material: glass\n  - plate: {point: [0.01, 0.005, 0.02], normal: [0, 0, 1], radius: 0.002}\n"
                    "    material: glass\n    motion: {velocity: [0.1, 0, 0]}\nparticles"),
               11, "walls[1]", "may not move along the periodic axis x");
}

// A face cannot be both periodic and open: a particle leaving through it wraps.
TEST(PeriodicScene, PeriodicFacesCannotBeOpen) {
  EXPECT_EQ(error_of(edit("periodic: [x, y]}", "periodic: [x, y], open: [zmax]}")), "(no error)");
  expect_error(edit("periodic: [x, y]}", "periodic: [x, y], open: [zmax, xmin]}"), 1, "domain.open[1]",
               "the face 'xmin' cannot be open: the axis x is periodic");
  expect_error(edit("periodic: [x, y]}", "open: [ymax], periodic: [x, y]}"), 1, "domain.open[0]",
               "the axis y is periodic");
}

// Insertion checks a candidate against the particles' periodic images
// (tests/engine/test_insertion_periodic.cpp): an inlet may reach the faces.
TEST(PeriodicScene, InletsMayReachThePeriodicFaces) {
  const std::string inlet = kChute + "inlets:\n  - name: feed\n    material: glass\n"
                                     "    region: {box: {min: [0.003, 0.003, 0.02], max: [0.017, 0.007, 0.028]}}\n"
                                     "    radius: 0.0005\n    rate: {count: 400}\n    total: {count: 40}\n";
  EXPECT_EQ(error_of(inlet), "(no error)");
  EXPECT_EQ(error_of(edit("min: [0.003, 0.003, 0.02]", "min: [0, 0, 0.02]", inlet)), "(no error)");
}

// Flows count on the segment between sampled centres, which a wrap would fake.
TEST(PeriodicScene, FlowsAreRefused) {
  const std::string flow = kChute + "measurements:\n  flows:\n"
                                    "    - {name: base, plane: {point: [0.01, 0.005, 0.005], normal: [1, 0, 0]}, every: 0.01}\n";
  expect_error(flow, 16, "measurements.flows", "cannot be measured in a periodic scene");
  EXPECT_EQ(error_of(edit(", periodic: [x, y]", "", flow)), "(no error)");
}

TEST(PeriodicScene, ParticlesOutsideTheBoxAreRefused) {
  const std::string msg = error_of(edit("max: [0.019, 0.009, 0.0092]", "max: [0.025, 0.009, 0.0092]"));
  EXPECT_NE(msg.find("not inside the domain"), std::string::npos) << msg;
}

TEST(PeriodicScene, ImageCountsOnlyForPeriodicRuns) {
  const std::string with_image = kChute + "output: {fields: [id, image]}\n";
  EXPECT_EQ(error_of(with_image), "(no error)");
  expect_error(edit(", periodic: [x, y]", "", with_image), 15, "output.fields", "only by periodic runs");
}

}  // namespace
}  // namespace gs
