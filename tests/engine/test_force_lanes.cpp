// Lanes per particle in the GPU's force computation (backend/backend.hpp,
// force_lanes; engine/force_kernel.hpp, in_group): a scene too small to fill
// the GPU gives each particle a group of lanes, which must add the same
// contacts in the same order as one thread does, so that the state has the
// same bits whatever the group's size. GRAINSTORM_FORCE_LANES chooses the size;
// anything but auto, 1, 2, 4, 8, 16 or 32 is refused by name.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "backend/backend.hpp"
#include "engine/simulation.hpp"
#include "io/state_digest.hpp"
#include "scene/scene_loader.hpp"
#include "support/support.hpp"

namespace gs {
namespace {

// Each test sets GRAINSTORM_FORCE_LANES as it needs; it is put back after.
class ForceLanesTest : public testing::Test {
 protected:
  static constexpr const char* kVariable = "GRAINSTORM_FORCE_LANES";
  test::ScopedEnv env_{kVariable, nullptr};
};

TEST_F(ForceLanesTest, UnknownSettingIsRefusedByName) {
  for (const char* bad : {"3", "64", "0", "many", "16 "}) {
    env_.set(bad);
    try {
      force_lanes_setting();
      ADD_FAILURE() << bad << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(kVariable), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST_F(ForceLanesTest, SettingIsTaken) {
  for (int lanes = 1; lanes <= kMaxForceLanes; lanes *= 2) {
    env_.set(std::to_string(lanes).c_str());
    EXPECT_EQ(force_lanes(10'000'000, force_lanes_setting()), lanes);
  }
  env_.set("auto");
  EXPECT_EQ(force_lanes_setting(), 0);
  EXPECT_EQ(force_lanes(10'000'000, force_lanes_setting()), 1);
}

// Unset: lanes only where one thread per particle leaves the GPU mostly idle,
// as many as keep the threads under kForceLaneThreads.
TEST_F(ForceLanesTest, AutomaticLanesServeOnlySmallScenes) {
  env_.set(nullptr);
  ASSERT_EQ(force_lanes_setting(), 0);
  EXPECT_EQ(force_lanes(7680, 0), 16);  // mixer case a
  EXPECT_EQ(force_lanes(100, 0), kMaxForceLanes);
  EXPECT_EQ(force_lanes(kForceLaneThreads, 0), 1);
  EXPECT_EQ(force_lanes(400'000'000, 0), 1);
  for (long long n : {1LL, 1000LL, 7680LL, 20000LL, 65536LL, 70000LL}) {
    const int lanes = force_lanes(n, 0);
    EXPECT_LE(n * lanes, kForceLaneThreads) << n;
    if (lanes < kMaxForceLanes) {
      EXPECT_GT(n * lanes * 2, kForceLaneThreads) << n << ": twice the lanes would fit";
    }
  }
}

// Mixer case a (7,680 spheres, friction, the impeller mesh, its hub fan of
// 64 triangles under which spheres touch more than kMeshInReachCap): 10,000
// steps, falling, settling, the impeller turning from t = 0.4 s (step 9,390),
// with groups of 1 to 32 lanes.
TEST_F(ForceLanesTest, GroupsOfLanesGiveTheBitsOfOneThread) {
  if (!cuda_device_available()) GTEST_SKIP() << "no CUDA device";
  const std::string here = __FILE__;
  const std::string scene_file = here.substr(0, here.rfind("tests/engine/")) + "cases/mixer/case_a_ci.yaml";
  if (!std::ifstream(scene_file)) GTEST_SKIP() << "no " << scene_file;
  const SceneSpec scene = load_scene(scene_file);
  constexpr long long kSteps = 10000;
  std::uint64_t one_thread = 0;
  for (const char* lanes : {"1", "2", "4", "16", "32"}) {
    env_.set(lanes);
    Simulation sim(scene, {Backend::cuda});
    sim.run(kSteps);
    const std::uint64_t digest = state_digest(sim.snapshot(), sim.history());
    const MeshLoad load = sim.mesh_loads().at(0);
    std::printf("lanes %s: digest 0x%016" PRIx64 ", torque on the impeller %.6g N m\n", lanes, digest, load.torque.z);
    EXPECT_NE(load.torque.z, 0.0) << "the spheres do not touch the impeller: the mesh path is not tested";
    if (lanes == std::string("1")) one_thread = digest;
    else EXPECT_EQ(digest, one_thread) << lanes << " lanes per particle";
  }
}

// A scene without a mesh gives one thread per particle a kernel with the
// mesh path compiled out (engine/force_kernel.hpp, WithoutMeshes), lanes the
// kernel with it: the same bits. The settling demo (2,000 frictional spheres
// in a box of six walls, 3,000 steps: falling, then a pile on the floor) and
// the periodic chute cell (rolling resistance, a plane base, two axes that
// wrap, 3,000 steps).
TEST_F(ForceLanesTest, WithoutAMeshOneThreadGivesTheBitsOfLanes) {
  if (!cuda_device_available()) GTEST_SKIP() << "no CUDA device";
  const std::string here = __FILE__;
  const std::string cases = here.substr(0, here.rfind("tests/engine/")) + "cases/";
  for (const char* file : {"demo/settle.yaml", "periodic/chute_cell.yaml"}) {
    SCOPED_TRACE(file);
    const SceneSpec scene = load_scene(cases + file);
    ASSERT_EQ(scene.meshes.n_triangles(), 0);
    std::uint64_t one_thread = 0;
    for (const char* lanes : {"1", "4"}) {
      env_.set(lanes);
      Simulation sim(scene, {Backend::cuda});
      sim.run(3000);
      const std::uint64_t digest = state_digest(sim.snapshot(), sim.history());
      std::printf("%s, lanes %s: digest 0x%016" PRIx64 "\n", file, lanes, digest);
      if (lanes == std::string("1")) one_thread = digest;
      else EXPECT_EQ(digest, one_thread) << lanes << " lanes per particle";
    }
  }
}

}  // namespace
}  // namespace gs
