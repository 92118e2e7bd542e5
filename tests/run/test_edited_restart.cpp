// A restart with an edited scene (run/edited_restart.hpp, scene/scene_edits.hpp):
// the stored springs against the scene's walls, contact slots and contact
// model, each checked against the rows written by hand here; the refusals;
// the edits listed value by value.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "core/types.hpp"
#include "run/edited_restart.hpp"
#include "scene/scene_edits.hpp"
#include "scene/scene_loader.hpp"
#include "walls/mesh.hpp"
#include "walls/sphere_triangle.hpp"
#include "walls/triangle_mesh.hpp"

namespace gs {
namespace {

// A box of six walls (xmin, xmax, ymin, ymax, zmin, zmax), one material,
// friction; `extra` goes at the end, `walls_first` before the box.
std::string scene_text(const std::string& walls_first = "", const std::string& extra = "") {
  return "domain: {min: [-0.01, -0.01, -0.01], max: [0.03, 0.03, 0.03]}\n"
         "gravity: [0, 0, -9.81]\n"
         "contact_model: linear\n"
         "effects: {friction: true}\n"
         "materials:\n  - {name: glass, density: 2500}\n"
         "pairs:\n  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5, friction: 0.5}\n"
         "walls:\n" +
         walls_first + "  - box: {min: [0, 0, 0], max: [0.02, 0.02, 0.02]}\n    material: glass\n" +
         "particles:\n  - list:\n      - {position: [0.005, 0.005, 0.001], radius: 0.001, material: glass}\n"
         "time_step: {fraction_of_contact_time: 0.1}\nduration: 0.01\n" + extra;
}

SceneSpec scene_of(const std::string& text) { return parse_scene(text, "edited.yaml", PackingChecks::by_caller); }

// Two particles resting on the floor (wall 4, zmin), particle 0 also against
// xmin (wall 0) and both against each other; 12 slots, the springs' x
// components 1, 2, 3 in particle 0's row and -3, 4 in particle 1's.
RestartState two_on_the_floor() {
  RestartState r;
  r.time = 0.005;
  for (int k = 0; k < 2; ++k) {
    r.particles.id.push_back(ParticleId(k));
    r.particles.material.push_back(0);
    r.particles.marker.push_back(0);
    r.particles.radius.push_back(0.001f);
    r.particles.position.push_back(Vec3d(0.001 + 0.002 * k, 0.005, 0.001));
  }
  HostHistory& h = r.particles.history;
  h.slots = 12;
  h.partner.assign(24, kNoPartner);
  h.tangential.assign(24, Vec3d());
  auto put = [&h](std::size_t row, std::size_t slot, ParticleId partner, double spring) {
    h.partner[row * 12 + slot] = partner;
    h.tangential[row * 12 + slot] = Vec3d(spring, 0, 0);
  };
  put(0, 0, kWallPartnerBase + 4, 1);
  put(0, 3, kWallPartnerBase + 0, 2);
  put(0, 7, 1, 3);
  put(1, 0, 0, -3);
  put(1, 1, kWallPartnerBase + 4, 4);
  return r;
}

std::vector<Wall> posed_walls(const SceneSpec& s) { return s.walls; }  // at rest: the pose at any time

TEST(EditedRestart, SpringsFollowTheirWallsToTheirNewIndices) {
  const std::vector<Wall> stored = posed_walls(scene_of(scene_text()));
  RestartState r = two_on_the_floor();
  const SceneSpec edited =
      scene_of(scene_text("  - plane: {point: [0, 0, 0.025], normal: [0, 0, -1]}\n    name: lid\n    material: glass\n"));
  const EditedRestart e = adapt_to_edited_scene(r, stored, edited);
  const HostHistory& h = r.particles.history;
  ASSERT_EQ(h.slots, 12);
  // Every box wall moved up by one index; slots and springs as they were.
  EXPECT_EQ(h.partner[0], kWallPartnerBase + 5);
  EXPECT_EQ(h.partner[3], kWallPartnerBase + 1);
  EXPECT_EQ(h.partner[7], ParticleId(1));
  EXPECT_EQ(h.partner[12 + 1], kWallPartnerBase + 5);
  EXPECT_EQ(h.tangential[3].x, 2);
  EXPECT_EQ(h.tangential[12 + 1].x, 4);
  EXPECT_EQ(e.new_walls, std::vector<std::string>{"lid"});
  EXPECT_TRUE(e.gone_walls.empty());
  EXPECT_EQ(e.dropped_wall_contacts, 0u);
}

TEST(EditedRestart, ContactsWithAWallThatIsGoneAreReleased) {
  // The box less its first wall (xmin): the others move down by one index.
  const std::vector<Wall> stored = posed_walls(scene_of(scene_text()));
  RestartState r = two_on_the_floor();
  SceneSpec edited = scene_of(scene_text());
  edited.walls.erase(edited.walls.begin());  // xmin gone
  edited.wall_names.erase(edited.wall_names.begin());
  const EditedRestart e = adapt_to_edited_scene(r, stored, edited);
  const HostHistory& h = r.particles.history;
  EXPECT_EQ(h.partner[0], kWallPartnerBase + 3);  // the floor, now wall 3
  EXPECT_EQ(h.partner[3], kNoPartner);             // xmin's contact released
  EXPECT_EQ(h.tangential[3].x, 0);
  EXPECT_EQ(e.gone_walls, std::vector<std::size_t>{0});
  EXPECT_EQ(e.dropped_wall_contacts, 1u);
}

TEST(EditedRestart, FewerSlotsPackTheRowsAndTooFewAreRefused) {
  const std::vector<Wall> stored = posed_walls(scene_of(scene_text()));
  RestartState r = two_on_the_floor();
  const EditedRestart e = adapt_to_edited_scene(r, stored, scene_of(scene_text("", "contact_slots: 3\n")));
  const HostHistory& h = r.particles.history;
  ASSERT_EQ(h.slots, 3);
  ASSERT_EQ(h.partner.size(), 6u);
  EXPECT_EQ(h.partner[0], kWallPartnerBase + 4);
  EXPECT_EQ(h.partner[1], kWallPartnerBase + 0);
  EXPECT_EQ(h.partner[2], ParticleId(1));
  EXPECT_EQ(h.tangential[1].x, 2);
  EXPECT_EQ(h.tangential[2].x, 3);
  EXPECT_EQ(h.partner[3], ParticleId(0));
  EXPECT_EQ(h.tangential[4].x, 4);
  EXPECT_EQ(h.partner[5], kNoPartner);
  EXPECT_EQ(e.slots_before, 12);
  EXPECT_EQ(e.slots_after, 3);

  RestartState again = two_on_the_floor();
  try {
    adapt_to_edited_scene(again, stored, scene_of(scene_text("", "contact_slots: 2\n")));
    FAIL() << "three contacts in two slots accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("particle 0 has 3 contacts"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("contact_slots (2)"), std::string::npos) << error.what();
  }
}

TEST(EditedRestart, ANewHistoryFieldStartsAtZeroAndADroppedOneGoes) {
  const std::vector<Wall> stored = posed_walls(scene_of(scene_text()));
  RestartState r = two_on_the_floor();
  std::string text = scene_text();
  text.replace(text.find("effects: {friction: true}"), 25, "effects: {friction: true, rolling_resistance: true}");
  text.replace(text.find("friction: 0.5}"), 14, "friction: 0.5, rolling_friction: 0.1}");
  const EditedRestart e = adapt_to_edited_scene(r, stored, scene_of(text));
  const HostHistory& h = r.particles.history;
  EXPECT_EQ(e.started_fields, unsigned(kRollingSprings));
  ASSERT_EQ(h.rolling.size(), 24u);
  EXPECT_EQ(h.rolling[7].x, 0);
  EXPECT_EQ(h.tangential[7].x, 3);

  RestartState frictionless = two_on_the_floor();
  text = scene_text();
  text.replace(text.find("effects: {friction: true}"), 25, "effects: {friction: false}");
  text.replace(text.find(", friction: 0.5}"), 16, "}");
  const EditedRestart f = adapt_to_edited_scene(frictionless, stored, scene_of(text));
  EXPECT_EQ(f.slots_after, 0);
  EXPECT_EQ(frictionless.particles.history.slots, 0);
  EXPECT_TRUE(frictionless.particles.history.partner.empty());
}

void expect_refused(RestartState r, const std::vector<Wall>& stored, const SceneSpec& scene,
                    const std::string& says) {
  try {
    adapt_to_edited_scene(r, stored, scene);
    FAIL() << "accepted; expected a refusal saying: " << says;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(says), std::string::npos) << error.what();
  }
}

TEST(EditedRestart, WhatTheStateCannotFollowIsRefused) {
  const std::string text = scene_text();
  const std::vector<Wall> stored = posed_walls(scene_of(text));
  RestartState unknown_material = two_on_the_floor();
  unknown_material.particles.material[1] = 1;
  expect_refused(unknown_material, stored, scene_of(text), "particle 1 at [0.003, 0.005, 0.001] is of material 1");

  RestartState outside = two_on_the_floor();
  outside.particles.position[0] = Vec3d(0.001, 0.005, 0.031);
  expect_refused(outside, stored, scene_of(text), "particle 0 at [0.001, 0.005, 0.031] is not inside");

  // A floor raised by 0.1 mm cuts 10 % into both spheres; by 5 um, 0.5 %.
  RestartState cut = two_on_the_floor();
  std::string raised = text;
  raised.replace(raised.find("box: {min: [0, 0, 0]"), 20, "box: {min: [0, 0, 0.0001]");
  expect_refused(cut, stored, scene_of(raised), "wall 'box.zmin', which the checkpoint does not have");
  RestartState touch = two_on_the_floor();
  std::string grazed = text;
  grazed.replace(grazed.find("box: {min: [0, 0, 0]"), 20, "box: {min: [0, 0, 0.000005]");
  const EditedRestart e = adapt_to_edited_scene(touch, stored, scene_of(grazed));
  EXPECT_EQ(e.new_walls, std::vector<std::string>{"box.zmin"});
  EXPECT_EQ(e.dropped_wall_contacts, 2u);  // both spheres' contacts with the old floor

  RestartState inlets = two_on_the_floor();
  inlets.insertion = InsertionState{};
  inlets.insertion->inlets.resize(1);
  expect_refused(inlets, stored, scene_of(text), "the checkpoint holds the state of 1 inlets, the edited scene has 0");
}

// The scene of scene_text() with a square mesh plate over the box's floor at
// height z: triangles (0, 0)-(L, 0)-(L, L) and (0, 0)-(L, L)-(0, L).
SceneSpec with_plate(double z) {
  SceneSpec s = scene_of(scene_text());
  TriangleMeshBuilder b("plate");
  const double l = 0.02;
  b.quad(b.vertex({0, 0, z}), b.vertex({l, 0, z}), b.vertex({l, l, z}), b.vertex({0, l, z}));
  add_mesh(s.meshes, b.take(), 0);
  return s;
}

TEST(EditedRestart, AMeshCuttingWhereNoContactWasIsRefused) {
  const std::vector<Wall> stored = posed_walls(scene_of(scene_text()));
  // Lowered onto the spheres' tops (z = 0.002) by 0.2 mm: 20 % of a radius.
  RestartState cut = two_on_the_floor();
  expect_refused(cut, stored, with_plate(0.0018),
                 "mesh 'plate' cuts 0.0002 m into particle 0 at [0.001, 0.005, 0.001] with radius 0.001");
  // Clear of them, or grazing them by 0.5 %: accepted.
  RestartState clear = two_on_the_floor(), grazed = two_on_the_floor();
  EXPECT_NO_THROW(adapt_to_edited_scene(clear, stored, with_plate(0.00201)));
  EXPECT_NO_THROW(adapt_to_edited_scene(grazed, stored, with_plate(0.001995)));
  // Where the checkpoint holds each sphere's contact with the face above it
  // (triangle 1: y > x), or with a feature next to it (triangle 0 shares
  // the diagonal), the mesh was there: the restart goes on.
  for (std::uint32_t face : {1u, 0u}) {
    RestartState touching = two_on_the_floor();
    HostHistory& h = touching.particles.history;
    h.partner[0 * 12 + 5] = mesh_partner_id(face);
    h.partner[1 * 12 + 5] = mesh_partner_id(face);
    EXPECT_NO_THROW(adapt_to_edited_scene(touching, stored, with_plate(0.0018))) << "face " << face;
  }
  // Only particle 0's contact is stored: particle 1 is named.
  RestartState one = two_on_the_floor();
  one.particles.history.partner[5] = mesh_partner_id(1);
  expect_refused(one, stored, with_plate(0.0018), "into particle 1 at [0.003, 0.005, 0.001]");
}

TEST(SceneDifferences, ValueByValue) {
  const std::string before = "a: 1\nb: {c: [1, 2, 3], d: x}  # comment\nlist:\n  - {k: 1}\n  - {k: 2}\ngone: 5\n";
  const std::string after = "# a comment\na: 1\nb:\n  c: [1, 2, 4]\n  d: x\nlist:\n  - {k: 1}\n  - {k: 3}\n"
                            "new: {deep: yes}\n";
  const std::vector<std::string> d = scene_differences(before, after);
  const std::vector<std::string> expected = {"changed b.c: [1, 2, 3] -> [1, 2, 4]", "changed list[1].k: 2 -> 3",
                                             "added new.deep: yes", "removed gone: 5"};
  EXPECT_EQ(d, expected);
  EXPECT_TRUE(scene_differences(before, "# only a comment\n" + before).empty());
  EXPECT_EQ(scene_differences(before, "a: [1\n"), std::vector<std::string>{"the scene text is not YAML"});
}

}  // namespace
}  // namespace gs
