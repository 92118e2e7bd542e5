// The scene keys of removal: `outlets:` and `domain.open` (docs/SCENES.md).
// Good input gives the regions and faces; bad input an error that names the
// file, the line and the key.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/particle_removal.hpp"
#include "scene/scene_loader.hpp"
#include "scene_test_helpers.hpp"

namespace gs {
namespace {

// Line numbers matter: the error tests check them. Outlets go on line 12.
const std::string kScene = R"(domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.2]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
particles:
  - lattice: {material: glass, radius: 0.001, min: [0.01, 0.01, 0.1], max: [0.02, 0.02, 0.11], spacing: 0.003}
time_step: {fraction_of_contact_time: 0.1}
duration: 0.5
output: {directory: res}
)";

std::string with_domain(const std::string& domain) {
  return domain + kScene.substr(kScene.find('\n'));
}

void expect_error(const std::string& text, int line, const std::string& key, const std::string& what) {
  test::expect_scene_error(text, line, key, what);
}

TEST(SceneOutlets, NoneByDefault) {
  const SceneSpec s = parse_scene(kScene, "scene.yaml");
  EXPECT_TRUE(s.outlets.empty());
  EXPECT_EQ(s.open_faces, 0u);
  EXPECT_FALSE(exits_of(s.outlets, s.open_faces).any());
}

TEST(SceneOutlets, RegionsNamesAndOpenFaces) {
  const SceneSpec s = parse_scene(with_domain("domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.2], open: [zmin, xmax]}") +
                                      "outlets:\n"
                                      "  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.01]}\n"
                                      "  - {name: orifice, cylinder: {base: [0.05, 0.05, 0], axis: [0, 0, 2], "
                                      "radius: 0.01, length: 0.02}}\n"
                                      "  - half_space: {point: [0, 0, 0.19], normal: [0, 0, 3]}\n"
                                      "  - box: {min: [0.09, 0, 0], max: [0.3, 0.1, 0.2]}\n",
                                  "scene.yaml");
  EXPECT_EQ(s.open_faces, (1u << 4) | (1u << 1));
  ASSERT_EQ(s.outlets.size(), 4u);
  EXPECT_EQ(s.outlets[0].name, "box");
  EXPECT_EQ(s.outlets[1].name, "orifice");
  EXPECT_EQ(s.outlets[2].name, "half_space");
  EXPECT_EQ(s.outlets[3].name, "box2");
  const OutletRegion& c = s.outlets[1].region;
  EXPECT_EQ(c.kind, OutletRegion::Kind::cylinder);
  EXPECT_DOUBLE_EQ(c.direction.z, 1.0);
  EXPECT_TRUE(outlet_contains(c, Vec3d(0.055, 0.05, 0.01)));
  EXPECT_FALSE(outlet_contains(c, Vec3d(0.065, 0.05, 0.01)));   // off the axis by more than the radius
  EXPECT_FALSE(outlet_contains(c, Vec3d(0.05, 0.05, 0.021)));   // above its top
  EXPECT_TRUE(outlet_contains(s.outlets[2].region, Vec3d(0.5, 0.5, 0.19)));  // on its plane
  EXPECT_FALSE(outlet_contains(s.outlets[2].region, Vec3d(0, 0, 0.189)));
  // Exits: the outlets in scene order, then the open faces from xmin to zmax.
  const Exits e = exits_of(s.outlets, s.open_faces);
  EXPECT_EQ(e.names, (std::vector<std::string>{"box", "orifice", "half_space", "box2", "domain.xmax", "domain.zmin"}));
  const ExitOf exit_of{e.outlets.data(), 4, e.open_faces, s.domain_min, s.domain_max};
  EXPECT_EQ(exit_of(Vec3d(0.05, 0.05, 0.005)), 0);   // in the box and the cylinder: the first
  EXPECT_EQ(exit_of(Vec3d(0.05, 0.05, 0.015)), 1);
  EXPECT_EQ(exit_of(Vec3d(0.05, 0.05, 0.1)), kNoExit);
  EXPECT_EQ(exit_of(Vec3d(0.2, 0.05, 0.1)), 3);      // beyond xmax, but in box2 first
  EXPECT_EQ(exit_of(Vec3d(0.05, 0.05, -0.01)), 5);   // below zmin, under no outlet
  const ExitOf faces_only{nullptr, 0, e.open_faces, s.domain_min, s.domain_max};
  EXPECT_EQ(faces_only(Vec3d(0.2, 0.05, 0.1)), 0);   // domain.xmax
  EXPECT_EQ(faces_only(Vec3d(0.05, 0.05, -0.1)), 1);  // domain.zmin
  EXPECT_EQ(faces_only(Vec3d(0.05, 0.05, 0.3)), kNoExit);  // zmax is closed: a fault, not an exit
}

TEST(SceneOutlets, BadOpenFaces) {
  expect_error(with_domain("domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.2], open: [z_min]}"), 1, "domain.open[0]",
               "'z_min' is not one of {xmin, xmax, ymin, ymax, zmin, zmax}");
  expect_error(with_domain("domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.2], open: [zmin, zmin]}"), 1,
               "domain.open[1]", "listed twice");
  expect_error(with_domain("domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.2], open: zmin}"), 1, "domain.open",
               "expected a list");
  expect_error(with_domain("domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.2], opn: [zmin]}"), 1, "domain.opn",
               "unknown key 'opn'; allowed here: min, max, open");
}

TEST(SceneOutlets, BadOutlets) {
  expect_error(kScene + "outlet: []\n", 12, "outlet", "unknown key 'outlet'");
  expect_error(kScene + "outlets:\n  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.01]}\n    nme: a\n", 14,
               "outlets[0].nme", "unknown key 'nme'; allowed here: box, cylinder, half_space, name");
  expect_error(kScene + "outlets:\n  - {name: a}\n", 13, "outlets[0]",
               "needs exactly one of {box, cylinder, half_space}");
  expect_error(kScene + "outlets:\n  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.01]}\n    cylinder: {}\n", 13,
               "outlets[0]", "needs exactly one of {box, cylinder, half_space}, got {box, cylinder}");
  // Zero-size regions.
  expect_error(kScene + "outlets:\n  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0]}\n", 13, "outlets[0].box",
               "must be below max");
  expect_error(kScene + "outlets:\n  - cylinder: {base: [0, 0, 0], axis: [0, 0, 1], radius: 0, length: 0.1}\n", 13,
               "outlets[0].cylinder.radius", "must be > 0");
  expect_error(kScene + "outlets:\n  - cylinder: {base: [0, 0, 0], axis: [0, 0, 1], radius: 0.1, length: 0}\n", 13,
               "outlets[0].cylinder.length", "must be > 0");
  expect_error(kScene + "outlets:\n  - cylinder: {base: [0, 0, 0], axis: [0, 0, 0], radius: 0.1, length: 0.1}\n",
               13, "outlets[0].cylinder.axis", "must not be the zero vector");
  expect_error(kScene + "outlets:\n  - half_space: {point: [0, 0, 0], normal: [0, 0, 0]}\n", 13,
               "outlets[0].half_space.normal", "must not be the zero vector");
  expect_error(kScene + "outlets:\n  - half_space: {point: [0, 0, 0]}\n", 13, "outlets[0].half_space",
               "missing required key 'normal'");
  // Outside the domain [0, 0.1] x [0, 0.1] x [0, 0.2].
  expect_error(kScene + "outlets:\n  - box: {min: [0, 0, -0.1], max: [0.1, 0.1, 0]}\n", 13, "outlets[0].box",
               "the outlet lies outside the domain");
  expect_error(kScene + "outlets:\n  - cylinder: {base: [0.05, 0.05, 0.2], axis: [0, 0, 1], radius: 0.01, "
                        "length: 0.1}\n",
               13, "outlets[0].cylinder", "the outlet lies outside the domain");
  expect_error(kScene + "outlets:\n  - cylinder: {base: [0.15, 0.05, 0.1], axis: [1, 0, 0], radius: 0.01, "
                        "length: 0.1}\n",
               13, "outlets[0].cylinder", "its bounding box");
  expect_error(kScene + "outlets:\n  - half_space: {point: [0, 0, 0], normal: [0, 0, -1]}\n", 13,
               "outlets[0].half_space", "the outlet lies outside the domain");
  // Names.
  expect_error(kScene + "outlets:\n  - {name: a, box: {min: [0, 0, 0], max: [0.1, 0.1, 0.01]}}\n"
                        "  - {name: a, box: {min: [0, 0, 0.1], max: [0.1, 0.1, 0.11]}}\n",
               14, "outlets[1].name", "outlet name 'a' is used twice");
  expect_error(kScene + "outlets:\n  - {name: domain.zmin, box: {min: [0, 0, 0], max: [0.1, 0.1, 0.01]}}\n", 13,
               "outlets[0].name", "kept for the open faces");
  expect_error(kScene + "outlets: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.01]}}\n", 12, "outlets",
               "expected a list");
}

TEST(SceneOutlets, ATiltedCylinderReachesIntoTheDomainByItsBoundingBox) {
  // Axis along x from outside the domain: its far end reaches in.
  const SceneSpec s = parse_scene(
      kScene + "outlets:\n  - cylinder: {base: [-0.05, 0.05, 0.1], axis: [1, 0, 0], radius: 0.01, length: 0.06}\n",
      "scene.yaml");
  ASSERT_EQ(s.outlets.size(), 1u);
  EXPECT_TRUE(outlet_contains(s.outlets[0].region, Vec3d(0.005, 0.05, 0.105)));
  EXPECT_FALSE(outlet_contains(s.outlets[0].region, Vec3d(0.015, 0.05, 0.1)));
}

}  // namespace
}  // namespace gs
