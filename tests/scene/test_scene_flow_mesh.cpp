// A mesh surface for a flow (`measurements.flows[i].mesh`, docs/SCENES.md):
// read from an STL file relative to the scene file, scaled, and every bad
// value refused with the file, line and key.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include <unistd.h>

#include "scene/scene_loader.hpp"
#include "scene_test_helpers.hpp"
#include "walls/stl.hpp"

namespace gs {
namespace {

// Line numbers below matter: the flow is on line 13.
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
measurements:
  flows:
    - {name: funnel, mesh: {stl: square_mm.stl, scale: 0.001}, every: 0.01, markers: [2]}
)";

class SceneFlowMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    // A 40 mm x 20 mm square at z = 50 mm, in millimetres, beside the scene file.
    dir_ = ::testing::TempDir() + "gs_flow_mesh_" + std::to_string(::getpid()) + "_";
    TriangleMeshBuilder b("square");
    b.quad(b.vertex({30, 40, 50}), b.vertex({30, 60, 50}), b.vertex({70, 60, 50}), b.vertex({70, 40, 50}));
    write_stl(dir_ + "square_mm.stl", b.take(), StlFormat::ascii);
  }
  void TearDown() override { std::remove((dir_ + "square_mm.stl").c_str()); }
  std::string scene_file() const { return dir_ + "scene.yaml"; }
  std::string dir_;
};

TEST_F(SceneFlowMesh, ReadsTheFileBesideTheSceneScaled) {
  const SceneSpec s = parse_scene(test::edited(kScene, "square_mm.stl", dir_ + "square_mm.stl"), "scene.yaml");
  ASSERT_EQ(s.measurements.flows.size(), 1u);
  const FlowSpec& f = s.measurements.flows[0];
  EXPECT_EQ(f.bound, FlowBound::mesh);
  ASSERT_EQ(f.surface.triangles.size(), 2u);
  Vec3d lo, hi;
  mesh_bounds(f.surface, lo, hi);
  EXPECT_DOUBLE_EQ(lo.x, 0.03);
  EXPECT_DOUBLE_EQ(hi.y, 0.06);
  EXPECT_DOUBLE_EQ(hi.z, 0.05);
  EXPECT_EQ(f.markers, std::vector<int>{2});
  // A relative path is taken from the scene file's directory.
  const std::string relative = "gs_flow_mesh_" + std::to_string(::getpid()) + "_square_mm.stl";
  const SceneSpec r = parse_scene(test::edited(kScene, "square_mm.stl", relative), ::testing::TempDir() + "scene.yaml");
  EXPECT_EQ(r.measurements.flows[0].surface.triangles.size(), 2u);
}

TEST_F(SceneFlowMesh, BadValuesNameTheirKey) {
  const std::string good = test::edited(kScene, "square_mm.stl", dir_ + "square_mm.stl");
  auto expect_error = [&](const std::string& from, const std::string& to, const std::string& key,
                          const std::string& what) {
    test::expect_scene_error(test::edited(good, from, to), 13, key, what);
  };
  expect_error("mesh: {", "plane: {point: [0.05, 0.05, 0.05], normal: [0, 0, 1]}, mesh: {", "measurements.flows[0].mesh",
               "not both");
  expect_error("every: 0.01", "radius: 0.01, every: 0.01", "measurements.flows[0].radius", "bounds a plane");
  expect_error("scale: 0.001", "scale: 0.01", "measurements.flows[0].mesh", "reaches outside the domain");
  expect_error("scale: 0.001", "scale: -1", "measurements.flows[0].mesh.scale", "> 0");
  expect_error("scale: 0.001", "scale: 0.001, crease_angle: 30", "measurements.flows[0].mesh.crease_angle",
               "unknown key");
  expect_error("square_mm.stl", "missing.stl", "measurements.flows[0].mesh.stl", "missing.stl");
}

}  // namespace
}  // namespace gs
