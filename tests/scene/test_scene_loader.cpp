#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <fstream>

#include "scene/scene_time_step.hpp"
#include "scene/particle_sources.hpp"
#include "scene/scene_loader.hpp"
#include "scene_test_helpers.hpp"

namespace gs {
namespace {

// Line numbers below matter: the error tests check them.
const std::string kGood = R"(domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}
gravity: [0, 0, -9.81]
effects: {friction: true}
materials:
  - {name: glass, density: 2500}
  - {name: steel, density: 7800}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5, friction: 0.4}
  - {materials: [steel, glass], stiffness_normal: 2000, restitution: 0.6}
walls:
  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}
    material: steel
particles:
  - lattice: {material: glass, radius: 0.001, min: [0.01, 0.01, 0.01], max: [0.019, 0.029, 0.039], spacing: 0.003}
  - list:
      - {position: [0.05, 0.05, 0.05], radius: 0.002, material: glass, velocity: [1, 0, 0], marker: 7}
time_step: {fraction_of_contact_time: 0.1}
duration: 0.5
output: {interval: 0.01, directory: res}
)";

// kGood with the first occurrence of `from` replaced by `to`.
std::string edit(const std::string& from, const std::string& to, const std::string& text = kGood) {
  return test::edited(text, from, to);
}

std::string error_of(const std::string& text) { return test::scene_error_of(text); }

void expect_error(const std::string& text, int line, const std::string& key, const std::string& what) {
  test::expect_scene_error(text, line, key, what);
}

TEST(SceneLoader, GoodSceneParses) {
  const SceneSpec s = parse_scene(kGood, "scene.yaml");
  EXPECT_EQ(s.path, "scene.yaml");
  EXPECT_EQ(s.domain_max.y, 0.1);
  EXPECT_EQ(s.gravity.z, -9.81);
  EXPECT_EQ(s.model, ContactModel::linear);
  EXPECT_EQ(s.precision, Precision::fp32);
  EXPECT_EQ(s.effects, unsigned(kFriction));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[1].name, "steel");
  EXPECT_EQ(s.materials[1].density, 7800);

  ASSERT_EQ(s.pairs.size(), 2u);
  EXPECT_EQ(s.pairs[1].material_a, 0);  // written [steel, glass], stored ordered
  EXPECT_EQ(s.pairs[1].material_b, 1);
  EXPECT_EQ(s.pairs[0].friction, 0.4);
  EXPECT_EQ(s.pairs[1].friction, 0);
  EXPECT_DOUBLE_EQ(s.pairs[0].stiffness_tangential, 2000.0 / 7.0);
  EXPECT_DOUBLE_EQ(s.pairs[0].stiffness_rolling, 2000.0 / 7.0);
  EXPECT_EQ(s.pairs[1].restitution, 0.6);

  ASSERT_EQ(s.lattices.size(), 1u);  // kept as its description, not as particles
  const std::vector<ParticleInit> all = all_particles(s);
  ASSERT_EQ(all.size(), 4u * 7u * 10u + 1u);
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i].id, i);
  const ParticleInit& last = all.back();
  EXPECT_EQ(last.radius, 0.002);
  EXPECT_EQ(last.velocity.x, 1);
  EXPECT_EQ(last.marker, 7);
  EXPECT_EQ(last.material, 0);
  EXPECT_EQ(all[0].position.x, 0.01);

  ASSERT_EQ(s.walls.size(), 6u);
  EXPECT_EQ(s.wall_names[0], "box.xmin");
  EXPECT_EQ(s.wall_names[5], "box.zmax");
  EXPECT_EQ(s.walls[0].material, 1);

  EXPECT_DOUBLE_EQ(s.contact_time, critical_contact_time(s));
  EXPECT_DOUBLE_EQ(s.time_step, 0.1 * s.contact_time);
  EXPECT_EQ(s.duration, 0.5);
  EXPECT_EQ(s.output.interval, 0.01);
  EXPECT_EQ(s.output.directory, "res");
  EXPECT_EQ(s.contact_slots, 12);
  EXPECT_EQ(s.surface_slots, 4);
  EXPECT_EQ(s.verlet_skin, 0.1);
  EXPECT_EQ(parse_scene(edit("effects:", "verlet_skin: 0.3\neffects:"), "s").verlet_skin, 0.3);
}

TEST(SceneLoader, BoxExpandsToSixInwardPlanes) {
  const SceneSpec s = parse_scene(edit("max: [0.1, 0.1, 0.1]}\n    material", "max: [0.1, 0.2, 0.1]}\n    name: bin\n    material",
                                       edit("max: [0.1, 0.1, 0.1]}\ngravity", "max: [0.1, 0.2, 0.1]}\ngravity")),
                                  "s");
  ASSERT_EQ(s.walls.size(), 6u);
  const Vec3d centre(0.05, 0.1, 0.05);
  const char* names[] = {"bin.xmin", "bin.xmax", "bin.ymin", "bin.ymax", "bin.zmin", "bin.zmax"};
  for (int w = 0; w < 6; ++w) {
    const Wall& wall = s.walls[w];
    EXPECT_EQ(wall.kind, WallKind::plane);
    EXPECT_EQ(s.wall_names[w], names[w]);
    EXPECT_DOUBLE_EQ(norm(wall.normal), 1.0);
    // Inward: the box centre is on the side the normal points to, at the half width.
    const double half[] = {0.05, 0.05, 0.1, 0.1, 0.05, 0.05};
    EXPECT_NEAR(dot(centre - wall.point, wall.normal), half[w], 1e-12) << names[w];
  }
}

const std::string kCylinder = R"(domain: {min: [-1, -1, -1], max: [1, 1, 1]}
materials: [{name: a, density: 1000}]
pairs: [{materials: [a, a], stiffness_normal: 100, restitution: 0.9}]
walls:
  - cylinder: {base: [0, 0, -0.5], axis: [0, 0, 2], radius: 0.3, length: 1, caps: both}
    material: a
    motion: {velocity: [0, 0, 0.1], rotation: {axis_point: [0, 0, 0], axis: [0, 0, 5], rpm: 60}}
particles:
  - list: [{position: [0, 0, 0], radius: 0.1, material: a}]
time_step: {absolute: 1e-5}
duration: 1
)";

TEST(SceneLoader, CylinderWithCapsAndMotion) {
  const SceneSpec s = parse_scene(kCylinder, "c");
  ASSERT_EQ(s.walls.size(), 3u);
  EXPECT_EQ(s.wall_names[0], "cylinder");
  EXPECT_EQ(s.wall_names[1], "cylinder.bottom");
  EXPECT_EQ(s.wall_names[2], "cylinder.top");
  const Wall &side = s.walls[0], &bottom = s.walls[1], &top = s.walls[2];
  EXPECT_EQ(side.kind, WallKind::cylinder);
  EXPECT_EQ(side.normal.z, 1);  // axis normalised
  EXPECT_EQ(side.radius, 0.3);
  EXPECT_EQ(side.length, 1);
  EXPECT_EQ(bottom.kind, WallKind::disk);
  EXPECT_EQ(bottom.point.z, -0.5);
  EXPECT_EQ(bottom.normal.z, 1);
  EXPECT_EQ(bottom.radius, 0.3);
  EXPECT_EQ(top.kind, WallKind::disk);
  EXPECT_EQ(top.point.z, 0.5);
  EXPECT_EQ(top.normal.z, -1);
  for (const Wall& w : s.walls) {
    EXPECT_EQ(w.velocity.z, 0.1);
    EXPECT_DOUBLE_EQ(w.angular_velocity.z, 2 * M_PI);  // 60 rpm
    EXPECT_EQ(w.axis_point.x, 0);
  }
  EXPECT_EQ(s.time_step, 1e-5);

  EXPECT_EQ(parse_scene(edit("caps: both", "caps: bottom", kCylinder), "c").walls.size(), 2u);
  EXPECT_EQ(parse_scene(edit(", caps: both", "", kCylinder), "c").walls.size(), 1u);
}

TEST(SceneLoader, WallPenetrationGeometry) {
  Wall plane;
  plane.point = Vec3d(0, 0, 1);
  plane.normal = Vec3d(0, 0, 1);
  EXPECT_NEAR(wall_penetration(plane, Vec3d(5, 5, 1.25), 0.5), 0.25, 1e-12);
  EXPECT_LT(wall_penetration(plane, Vec3d(5, 5, 1.75), 0.5), 0);
  EXPECT_GT(wall_penetration(plane, Vec3d(5, 5, 0.0), 0.5), 0);  // behind the plane

  Wall disk = plane;
  disk.kind = WallKind::disk;
  disk.radius = 1;
  EXPECT_NEAR(wall_penetration(disk, Vec3d(0.5, 0, 0.75), 0.5), 0.25, 1e-12);
  EXPECT_LT(wall_penetration(disk, Vec3d(0.5, 0, -1), 0.5), 0);   // far behind: clear
  EXPECT_LT(wall_penetration(disk, Vec3d(2, 0, 1), 0.5), 0);      // beside the rim
  EXPECT_NEAR(wall_penetration(disk, Vec3d(1.3, 0, 1), 0.5), 0.2, 1e-12);  // touching the rim

  Wall cyl;
  cyl.kind = WallKind::cylinder;
  cyl.normal = Vec3d(0, 0, 1);
  cyl.radius = 1;
  cyl.length = 2;
  EXPECT_NEAR(wall_penetration(cyl, Vec3d(0.75, 0, 1), 0.5), 0.25, 1e-12);
  EXPECT_LT(wall_penetration(cyl, Vec3d(0.25, 0, 1), 0.5), 0);
  EXPECT_LT(wall_penetration(cyl, Vec3d(3, 0, 2.5), 0.5), 0);  // beyond the length: not checked
}

TEST(SceneLoader, MarkingAndMotionStart) {
  const SceneSpec s = parse_scene(kGood + "marking: {time: 0.25, plane: {point: [0.05, 0, 0], normal: [2, 0, 0]}, "
                                          "front: 1, back: 0}\n", "scene.yaml");
  ASSERT_TRUE(s.marking.has_value());
  EXPECT_EQ(s.marking->time, 0.25);
  EXPECT_EQ(s.marking->point.x, 0.05);
  EXPECT_EQ(s.marking->normal.x, 1);  // normalised
  EXPECT_EQ(s.marking->front, 1);
  EXPECT_EQ(s.marking->back, 0);
  EXPECT_FALSE(parse_scene(kGood, "scene.yaml").marking.has_value());
  const SceneSpec c = parse_scene(edit("rpm: 60}", "rpm: 60}, start: 0.5", kCylinder), "c");
  for (const Wall& w : c.walls) EXPECT_EQ(w.motion_start, 0.5);

  expect_error(kGood + "marking: {time: 0.6, plane: {point: [0, 0, 0], normal: [1, 0, 0]}, front: 1, back: 0}\n", 20,
               "marking.time", "must not exceed the duration");
  expect_error(kGood + "marking: {time: 0.1, plane: {point: [0, 0, 0], normal: [0, 0, 0]}, front: 1, back: 0}\n", 20,
               "marking.plane.normal", "zero vector");
  expect_error(kGood + "marking: {time: 0.1, plane: {point: [0, 0, 0], normal: [1, 0, 0]}, front: 1}\n", 20,
               "marking", "missing required key 'back'");
  const std::string negative_start = error_of(edit("rpm: 60}", "rpm: 60}, start: -1", kCylinder));
  EXPECT_NE(negative_start.find("motion.start"), std::string::npos) << negative_start;
  EXPECT_NE(negative_start.find(">= 0"), std::string::npos) << negative_start;
}

TEST(SceneLoaderErrors, UnknownKeys) {
  expect_error(kGood + "gravty: [0, 0, 1]\n", 20, "gravty", "allowed here: domain, gravity");
  expect_error(edit("spacing: 0.003", "spacng: 0.003"), 14, "particles[0].lattice.spacng", "unknown key");
  expect_error(edit("effects: {friction: true}", "effects: {fiction: true}"), 3, "effects.fiction", "rolling_resistance");
}

TEST(SceneLoaderErrors, MissingRequiredKeys) {
  expect_error(edit("duration: 0.5\n", ""), 1, "scene", "missing required key 'duration'");
  expect_error(edit("{name: steel, density: 7800}", "{name: steel}"), 6, "materials[1]", "'density'");
  expect_error(edit("restitution: 0.6}", "friction: 0.1}"), 9, "pairs[1]", "'restitution'");
}

TEST(SceneLoaderErrors, WrongTypes) {
  expect_error(edit("duration: 0.5", "duration: half"), 18, "duration", "expected a finite number");
  expect_error(edit("gravity: [0, 0, -9.81]", "gravity: [0, -9.81]"), 2, "gravity", "list of 3 numbers");
  expect_error(edit("friction: true", "friction: maybe"), 3, "effects.friction", "true or false");
  expect_error(edit("marker: 7", "marker: 700"), 16, "particles[1].list[0].marker", "[0, 255]");
  expect_error(edit("output: {interval: 0.01, directory: res}", "output: [0.01]"), 19, "output", "expected a map");
}

TEST(SceneLoaderErrors, NonPositiveValues) {
  expect_error(edit("radius: 0.001", "radius: 0"), 14, "particles[0].lattice.radius", "must be > 0");
  expect_error(edit("density: 2500", "density: -1"), 5, "materials[0].density", "must be > 0");
  expect_error(edit("stiffness_normal: 1000", "stiffness_normal: 0"), 8, "pairs[0].stiffness_normal", "> 0");
  expect_error(edit("duration: 0.5", "duration: -2"), 18, "duration", "must be > 0");
  expect_error(edit("restitution: 0.5", "restitution: 1.5"), 8, "pairs[0].restitution", "(0, 1]");
  expect_error(edit("restitution: 0.5", "restitution: 0"), 8, "pairs[0].restitution", "(0, 1]");
  expect_error(edit("friction: 0.4", "friction: -0.1"), 8, "pairs[0].friction", ">= 0");
}

TEST(SceneLoaderErrors, UnknownMaterial) {
  expect_error(edit("material: glass, velocity", "material: glas, velocity"), 16, "particles[1].list[0].material",
               "unknown material 'glas'");
  expect_error(edit("material: steel", "material: iron"), 12, "walls[0].material", "glass, steel");
  expect_error(edit("[steel, glass]", "[steel, gold]"), 9, "pairs[1].materials[1]", "'gold'");
}

TEST(SceneLoaderErrors, ParticleOutsideDomain) {
  expect_error(edit("position: [0.05, 0.05, 0.05]", "position: [0.0999, 0.05, 0.05]"), 16, "particles[1].list[0]",
               "not inside the domain");
  expect_error(edit("max: [0.019, 0.029, 0.039]", "max: [0.019, 0.029, 0.1]"), 14, "particles[0].lattice",
               "not inside the domain");
}

TEST(SceneLoaderErrors, ParticleCutsIntoWall) {
  const std::string plane = edit("  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}", "  - plane: {point: [0, 0, 0.049], normal: [0, 0, -3]}");
  expect_error(plane, 16, "particles[1].list[0]", "into wall 'plane'");
  const std::string cyl = edit("  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}",
                               "  - cylinder: {base: [0.02, 0.05, 0], axis: [0, 0, 1], radius: 0.03, length: 0.1}");
  expect_error(cyl, 14, "particles[0].lattice", "into wall 'cylinder'");  // lattice corners stick out
  // A disk cap right under the list particle.
  const std::string cap = edit("radius: 0.03, length: 0.1}", "radius: 0.07, length: 0.0505, caps: top}",
                               edit("[0.02, 0.05, 0]", "[0.05, 0.05, 0]", cyl));
  expect_error(cap, 16, "particles[1].list[0]", "into wall 'cylinder.top'");
}

TEST(SceneLoaderErrors, ParticlesOverlapEachOther) {
  expect_error(edit("position: [0.05, 0.05, 0.05]", "position: [0.0115, 0.01, 0.01]"), 16, "particles[1].list[0]",
               "overlaps particle");
}

TEST(SceneLoaderErrors, BadDomainAndAxis) {
  expect_error(edit("max: [0.1, 0.1, 0.1]}\ngravity", "max: [0.1, 0, 0.1]}\ngravity"), 1, "domain", "must be below max");
  expect_error(edit("    material: steel\n", "    material: steel\n    motion: {rotation: {axis_point: [0, 0, 0], axis: [0, 0, 0], rpm: 10}}\n"),
               13, "walls[0].motion.rotation.axis", "zero vector");
}

// fp32_full keeps positions in fp32: accepted where fp32 resolves a
// thousandth of the smallest radius (1 mm here), refused at the `precision`
// key where it does not (fp32 spacing 6.1e-5 m at 1000 m).
TEST(SceneLoader, Fp32FullPrecision) {
  EXPECT_EQ(parse_scene(kGood + "precision: fp32_full\n", "scene.yaml").precision, Precision::fp32_full);
  EXPECT_EQ(parse_scene(kGood + "precision: fp64\n", "scene.yaml").precision, Precision::fp64);
  expect_error(edit("max: [0.1, 0.1, 0.1]}", "max: [1000, 0.1, 0.1]}") + "precision: fp32_full\n", 20, "precision",
               "fp32 positions are 6.1e-05 m apart");
  EXPECT_EQ(parse_scene(edit("max: [0.1, 0.1, 0.1]}", "max: [1000, 0.1, 0.1]}") + "precision: fp32\n", "scene.yaml")
                .precision,
            Precision::fp32);
  expect_error(kGood + "precision: fp16\n", 20, "precision", "fp32_full");
}

TEST(SceneLoaderErrors, TimeStepAboveStabilityLimit) {
  const std::string msg = error_of(edit("{fraction_of_contact_time: 0.1}", "{absolute: 0.001}"));
  EXPECT_EQ(msg.rfind("scene.yaml:17: time_step: time step 0.001 s (", 0), 0u) << msg;
  EXPECT_NE(msg.find("exceeds the stability limit"), std::string::npos) << msg;
  EXPECT_NE(msg.find("of the contact time), set by the "), std::string::npos) << msg;
  expect_error(edit("0.1}", "0.3}"), 17, "time_step", "stability limit");
}

// A run counts whole steps of the duration, its time their count times the
// step: none, or more than fp64 counts exactly, is refused.
TEST(SceneLoaderErrors, DurationOfNoStepOrTooManySteps) {
  expect_error(edit("{fraction_of_contact_time: 0.1}", "{absolute: 1e-300}"), 17, "time_step", "more than 2^53");
  expect_error(edit("duration: 0.5", "duration: 1e-9"), 17, "time_step", "the run would make no step");
  EXPECT_NO_THROW(parse_scene(edit("{fraction_of_contact_time: 0.1}", "{absolute: 1e-5}"), "scene.yaml"));
}

TEST(SceneLoaderErrors, MissingPairNamesBothMaterials) {
  expect_error(edit("  - {materials: [steel, glass], stiffness_normal: 2000, restitution: 0.6}\n", ""), 7, "pairs",
               "[glass, steel]");
  expect_error(edit("  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5, friction: 0.4}\n",
                    "  - {materials: [glass, steel], stiffness_normal: 1000, restitution: 0.5, friction: 0.4}\n"),
               9, "pairs[1].materials", "given twice");
}

TEST(SceneLoaderErrors, NoParticles) {
  const std::string list =
      "  - list:\n      - {position: [0.05, 0.05, 0.05], radius: 0.002, material: glass, velocity: [1, 0, 0], "
      "marker: 7}\n";
  const std::string empty = edit("  - lattice: {material: glass, radius: 0.001, min: [0.01, 0.01, 0.01], max: [0.019, "
                                 "0.029, 0.039], spacing: 0.003}\n",
                                 "  - list: []\n", edit(list, ""));
  expect_error(empty, 13, "particles", "no particles");
}

TEST(SceneLoaderErrors, SyntaxErrorHasLine) {
  const std::string msg = error_of(edit("  - {name: steel, density: 7800}", "  - {name: steel, density: [7800}"));
  EXPECT_EQ(msg.rfind("scene.yaml:6: ", 0), 0u) << msg;
  EXPECT_EQ(error_of("").rfind("scene.yaml:1: scene: expected a map", 0), 0u) << error_of("");
}

TEST(SceneLoaderErrors, SetShapeAndChoices) {
  expect_error(edit("  - list:\n", "  - lattice: {}\n    list:\n"), 15, "particles[1]", "exactly one of");
  expect_error(edit("effects:", "contact_model: hooke\neffects:"), 3, "contact_model", "linear, hertz_mindlin");
  expect_error(edit("effects:", "contact_slots: 33\neffects:"), 3, "contact_slots", "[1, 32]");
  expect_error(edit("effects:", "surface_slots: 0\neffects:"), 3, "surface_slots", "[1, 32]");
  expect_error(edit("effects:", "verlet_skin: -0.1\neffects:"), 3, "verlet_skin", ">= 0");
  expect_error(edit("effects:", "verlet_skin: 1.5\neffects:"), 3, "verlet_skin", "at most 1");
  expect_error(edit("effects:", "contact_model: hertz_mindlin\neffects:"), 6, "materials[0]", "'youngs_modulus'");
  expect_error(edit("spacing: 0.003", "spacing: 0.0019"), 14, "particles[0].lattice.spacing", "overlap");
  expect_error(edit("gravity: [0, 0, -9.81]", "gravity: [0, 0, -9.81]\ngravity: [0, 0, 0]"), 3, "gravity", "twice");
}

TEST(SceneLoaderErrors, RandomFillTooFull) {
  const std::string fill =
      "  - random_fill: {material: glass, count: 5000, radius: 0.002, seed: 1,\n"
      "                  region: {box: {min: [0.05, 0.05, 0.05], max: [0.08, 0.08, 0.08]}}}\n";
  expect_error(edit("  - list:\n", fill + "  - list:\n"), 15, "particles[1].random_fill", "too full");
}

// Below the up-front limit, but beyond what random addition reaches: the fill
// fails while its blocks are made for the fit check, at its own line.
TEST(SceneLoaderErrors, RandomFillBlockTooFullNamesItsLine) {
  const std::string fill =
      "  - random_fill: {material: glass, count: 403, radius: 0.002, seed: 1,\n"
      "                  region: {box: {min: [0.05, 0.05, 0.05], max: [0.08, 0.08, 0.08]}}}\n";
  expect_error(edit("  - list:\n", fill + "  - list:\n"), 15, "particles[1].random_fill", "no free spot");
}

TEST(SceneLoader, RandomFillAndDistributionInScene) {
  const std::string fill =
      "  - random_fill:\n"
      "      material: glass\n"
      "      region: {cylinder: {base: [0.06, 0.06, 0.01], axis: [0, 0, 1], radius: 0.03, length: 0.08}}\n"
      "      count: 1000\n"
      "      diameter_distribution: [{diameter: 0.002, fraction: 0.25}, {diameter: 0.001, fraction: 0.75}]\n";
  const SceneSpec s = parse_scene(edit("  - list:\n", fill + "  - list:\n"), "s");
  const std::vector<ParticleInit> all = all_particles(s);
  ASSERT_EQ(all.size(), 280u + 1000u + 1u);
  int big = 0;
  for (std::size_t i = 280; i < 1280; ++i) big += all[i].radius == 0.001;
  EXPECT_EQ(big, 250);
}

TEST(SceneLoader, DemoSceneLoads) {
  const std::string here = __FILE__;
  const std::string demo = here.substr(0, here.rfind("tests/scene/")) + "cases/demo/settle.yaml";
  if (!std::ifstream(demo)) GTEST_SKIP() << "no " << demo;
  const SceneSpec s = load_scene(demo);
  EXPECT_EQ(particle_count(s), 2000u);
  EXPECT_EQ(s.walls.size(), 6u);
  EXPECT_TRUE(s.effects & kFriction);
  // Cheap enough for the demo's one-minute budget: ~23k steps of 2000 spheres.
  EXPECT_LT(s.duration / s.time_step, 25000);
  EXPECT_THROW(load_scene(demo + ".missing"), SceneError);
}

// ---- issue 18: what run refused and check accepted, numbers that overflow,
// ignored parameters, extra documents and tags, huge echoed values ----------

TEST(SceneLoaderErrors, HugeDomainIsRefusedNotOneCell) {
  // 1e7 m in cells of 4 mm: 1.6e28 cells; the int conversion used to give 1 cell.
  for (const char* max : {"max: [1e7, 1e7, 1e7]", "max: [1e30, 0.1, 0.1]"})
    expect_error(edit("max: [0.1, 0.1, 0.1]", max), 1, "domain", "cells of at least 0.004 m");
}

TEST(SceneLoaderErrors, HugeLatticeIsRefusedNotOneLayer) {
  // 1e20 m / 3 mm sites along x: the size_t conversion used to give 16 spheres.
  expect_error(edit("max: [0.019, 0.029, 0.039]", "max: [1e20, 0.029, 0.039]"), 14, "particles[0].lattice",
               "more than the");
}

TEST(SceneLoaderErrors, ContactCountWithoutHistoryHasFileAndLine) {
  const std::string frictionless = edit("effects: {friction: true}", "effects: {cohesion: false}");
  expect_error(edit("output: {interval: 0.01, directory: res}",
                    "output: {interval: 0.01, directory: res, fields: [id, position, contact_count]}", frictionless),
               19, "output.fields", "contact_count needs a contact history");
  EXPECT_NO_THROW(parse_scene(edit("output: {interval: 0.01, directory: res}",
                                   "output: {interval: 0.01, directory: res, fields: [id, position, contact_count]}"),
                              "scene.yaml"));
  // The hysteretic law keeps a history (its peak overlaps) without any effect.
  const std::string hysteretic =
      edit("effects: {cohesion: false}", "contact_model: hysteretic_linear\neffects: {cohesion: false}", frictionless);
  EXPECT_NO_THROW(parse_scene(edit("output: {interval: 0.01, directory: res}",
                                   "output: {interval: 0.01, directory: res, fields: [id, position, contact_count]}",
                                   hysteretic),
                              "scene.yaml"));
}

TEST(SceneLoader, WarnsOfParametersOfEffectsThatAreOff) {
  EXPECT_TRUE(parse_scene(kGood, "scene.yaml").warnings.empty());
  const SceneSpec s = parse_scene(edit("effects: {friction: true}", "effects: {cohesion: false}"), "scene.yaml");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].rfind("scene.yaml:8: pairs[0].friction: ignored: the effect friction is off", 0), 0u)
      << s.warnings[0];
  // Every parameter of an effect that is off, with its line; a zero friction agrees with friction off.
  const std::string pair = "  - {materials: [steel, glass], stiffness_normal: 2000, restitution: 0.6}";
  const SceneSpec all = parse_scene(
      edit(pair,
           "  - {materials: [steel, glass], stiffness_normal: 2000, restitution: 0.6, friction: 0,\n"
           "     stiffness_tangential: 500, rolling_friction: 0.1, stiffness_rolling: 100, cohesion_energy_density: 5}",
           edit("effects: {friction: true}", "effects: {friction: false}")),
      "scene.yaml");
  const std::vector<std::string> keys = {"pairs[0].friction", "pairs[1].stiffness_tangential",
                                         "pairs[1].rolling_friction", "pairs[1].stiffness_rolling",
                                         "pairs[1].cohesion_energy_density"};
  ASSERT_EQ(all.warnings.size(), keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k)
    EXPECT_NE(all.warnings[k].find(keys[k]), std::string::npos) << all.warnings[k];
  EXPECT_EQ(all.warnings[1].rfind("scene.yaml:10: ", 0), 0u) << all.warnings[1];
}

TEST(SceneLoaderErrors, SecondDocumentIsRefused) {
  expect_error(kGood + "---\nduration: 1\n", 21, "yaml", "a second document");
}

TEST(SceneLoaderErrors, TagsAreRefused) {
  expect_error(edit("gravity: [0, 0, -9.81]", "gravity: !vec [0, 0, -9.81]"), 2, "'!vec'", "not supported");
  expect_error(edit("duration: 0.5", "duration: !!float 0.5"), 18, "tag:yaml.org,2002:float", "not supported");
  expect_error(edit("radius: 0.002", "radius: !custom 0.002"), 16, "'!custom'", "not supported");
  // Quoted values carry the non-specific tag "!", which is no tag.
  EXPECT_NO_THROW(parse_scene(edit("directory: res", "directory: \"res\""), "scene.yaml"));
}

TEST(SceneLoaderErrors, EchoedValuesAreCut) {
  const std::string huge(1000000, 'g');
  const std::string key(1000, 'k');  // YAML allows implicit keys up to 1024 characters
  for (const auto& [from, to, size] : std::vector<std::tuple<std::string, std::string, std::size_t>>{
           {"duration: 0.5", "duration: " + huge, huge.size()},              // not a number
           {"gravity: [0, 0, -9.81]", "gravity: " + huge, huge.size()},      // not a list
           {"material: steel", "material: " + huge, huge.size()},            // unknown material
           {"format: csv", "format: " + huge, huge.size()},                  // not a choice
           {"gravity:", key + ":", key.size()}}) {                            // unknown key
    const std::string msg = error_of(edit(from, to, edit("directory: res", "directory: res, format: csv")));
    EXPECT_LT(msg.size(), 700u) << msg.substr(0, 700);
    EXPECT_NE(msg.find("... (" + std::to_string(size) + " characters)"), std::string::npos) << msg.substr(0, 700);
  }
}

// An STL in millimetres read as metres: 300 m x 300 m under a 0.1 m domain.
TEST(SceneLoaderErrors, MeshInMillimetresIsRefusedBeforeBinning) {
  const std::string stl = testing::TempDir() + "/gs_plate_mm.stl";
  {
    std::ofstream f(stl);
    f << "solid plate\n";
    const double q[4][3] = {{-100, -100, -1}, {200, -100, -1}, {200, 200, -1}, {-100, 200, -1}};
    const int triangles[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& t : triangles) {
      f << "facet normal 0 0 1\nouter loop\n";
      for (int k = 0; k < 3; ++k) f << "vertex " << q[t[k]][0] << " " << q[t[k]][1] << " " << q[t[k]][2] << "\n";
      f << "endloop\nendfacet\n";
    }
    f << "endsolid plate\n";
  }
  const std::string wall = "  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}\n    material: steel\n";
  const std::string mm = wall + "  - mesh: {stl: " + stl + "}\n    material: steel\n";
  expect_error(edit(wall, mm), 13, "walls[1].mesh", "mesh 'mesh' spans [300, 300, 0] m against a domain of");
  EXPECT_NE(error_of(edit(wall, mm)).find("scale: 0.001"), std::string::npos);
  // In metres it is a 0.3 m plate below the domain, binned in a few thousand cells.
  const std::string m = wall + "  - mesh: {stl: " + stl + ", scale: 0.001}\n    material: steel\n";
  EXPECT_NO_THROW(parse_scene(edit(wall, m), "scene.yaml"));
}

// A mesh wall's STL file that is not there: the error names the entry's key
// and the file (the scene's directory before a relative name).
TEST(SceneLoaderErrors, MissingMeshFileNamesTheKeyAndTheFile) {
  const std::string wall = "  - box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}\n    material: steel\n";
  const std::string missing = wall + "  - mesh: {stl: gs_no_such_mesh.stl}\n    material: steel\n";
  test::expect_scene_error(edit(wall, missing), 13, "walls[1].mesh.stl", "runs/gs_no_such_mesh.stl", "runs/scene.yaml");
}

}  // namespace
}  // namespace gs
