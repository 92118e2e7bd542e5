// Rows of surface slots only where a wall or mesh can reach
// (engine/surface_rows.hpp): a run gives the bits of the same run with a row
// for every particle, also where a wall moves into a bed that does not move
// itself (so only the wall's drift, walls/wall_drift.hpp, calls for the
// builds that give the spheres it reaches their rows), and holds the rows of
// the spheres near its walls only.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>

#include "scene/scene_time_step.hpp"
#include "engine/simulation.hpp"
#include "io/state_digest.hpp"
#include "support/support.hpp"
#include "walls/mesh_test_helpers.hpp"

namespace gs::test {
namespace {

constexpr int kSide = 8;
constexpr double kRadius = 0.001, kSpacing = 0.002001;  // a gap of 1 um: nothing moves until a wall comes
constexpr long long kSteps = 130;

enum class Moving { lid, side, mesh_lid };

// A lattice of kSide^3 spheres, no gravity, in a box of four fixed walls 10
// um from the spheres (the floor and three sides) and one that moves in from
// 1 mm away: a lid coming down 10 um a step (a plane, or a square mesh of
// 200 triangles, whose spheres get rows through their near lists), or the
// fourth side turning inward about its foot (1.6 mm at the top over the run). The spheres stay
// still until the wall comes, so only the wall's drift calls for the builds
// that give the spheres it reaches their rows (the skin is 0.2 mm).
SceneSpec boxed_bed(Moving moving) {
  SceneSpec scene = base_scene(2500, 2000, 0.5, 0.5);
  scene.precision = Precision::fp32;
  scene.effects = kFriction;
  scene.gravity = {0, 0, 0};
  const double box = kSide * kSpacing, top = (kSide - 1) * kSpacing + 2 * kRadius;
  scene.domain_min = {-0.002, -0.002, -0.002};
  scene.domain_max = {box + 0.002, box + 0.002, box + 0.004};
  for (int z = 0; z < kSide; ++z)
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x)
        scene.particles.push_back(particle(ParticleId(scene.particles.size()), kRadius,
                                           {kRadius + x * kSpacing, kRadius + y * kSpacing, kRadius + z * kSpacing}));
  scene.contact_time = critical_contact_time(scene);
  scene.time_step = 0.02 * scene.contact_time;
  const double dt = scene.time_step, gap = 1e-5;
  scene.walls = {plane_wall({0, 0, -gap}, {0, 0, 1}), plane_wall({0, -gap, 0}, {0, 1, 0}),
                 plane_wall({0, box + gap, 0}, {0, -1, 0}), plane_wall({box + gap, 0, 0}, {-1, 0, 0})};
  if (moving == Moving::lid) {
    Wall lid = plane_wall({0, 0, top + 0.001}, {0, 0, -1});
    lid.velocity = {0, 0, -1e-5 / dt};
    scene.walls.push_back(lid);
  } else if (moving == Moving::mesh_lid) {
    const double h = (box + 0.002) / 10;
    MeshMotion down;
    down.velocity = {0, 0, -1e-5 / dt};
    add_mesh(scene.meshes, make_flat_square(10, h, 0.2, Rotation({0, 0, 1}, 0), {-0.001, -0.001, top + 0.001}, 3).mesh,
             0, down);
  } else {
    Wall side = plane_wall({-0.001, 0, 0}, {1, 0, 0});
    side.axis_point = {-0.001, 0, 0};
    side.angular_velocity = {0, 0.0016 / top / (double(kSteps) * dt), 0};  // its top inward (+x)
    scene.walls.push_back(side);
  }
  return scene;
}

struct Outcome {
  std::uint64_t digest;
  std::size_t wall_contacts;
  double mesh_force;  // along z
  double held_per_particle;
};

Outcome run(const SceneSpec& scene, Backend b, bool row_each) {
  RunOptions options{b};
  options.surface_row_for_every_particle = row_each;
  Simulation sim(scene, options);
  sim.run(kSteps);
  const ParticleRecords on_walls = sim.wall_contact_history();
  const std::vector<MeshLoad> mesh = sim.mesh_loads();
  return {state_digest(sim.snapshot(), sim.history()), on_walls.id.size(), mesh.empty() ? 0.0 : mesh[0].force.z,
          double(sim.device_bytes()) / double(sim.particle_count())};
}

class SurfaceRows : public testing::TestWithParam<Backend> {};

// touched: at least so many spheres on a wall at the end; or, where 0, the
// mesh pressing down on the bed.
void expect_the_bits_of_a_row_each(const SceneSpec& scene, Backend b, std::size_t touched) {
  const Outcome near = run(scene, b, false), each = run(scene, b, true);
  std::printf("rows near the walls 0x%016" PRIx64 " (%zu on walls, mesh force %.3g N, %.1f bytes per particle held), "
              "a row each 0x%016" PRIx64 " (%.1f)\n", near.digest, near.wall_contacts, near.mesh_force,
              near.held_per_particle, each.digest, each.held_per_particle);
  EXPECT_EQ(near.digest, each.digest);
  if (touched > 0) EXPECT_GE(near.wall_contacts, touched);  // the moving wall did press in
  else EXPECT_GT(near.mesh_force, 0);  // the mesh pressed in: the spheres push it back up
  // A row holds 4 slots of a partner id and a 12-byte spring: the 6^3
  // spheres inside the outer layers never need one.
  const double inner = 6.0 * 6 * 6 / (kSide * kSide * kSide);
  EXPECT_GT(each.held_per_particle - near.held_per_particle, 0.9 * inner * 4 * 16);
}

TEST_P(SurfaceRows, GiveTheBitsOfARowForEveryParticleAsALidComesDown) {
  expect_the_bits_of_a_row_each(boxed_bed(Moving::lid), GetParam(), kSide * kSide);  // the whole top layer
}

TEST_P(SurfaceRows, GiveTheBitsOfARowForEveryParticleAsASideTurnsIn) {
  expect_the_bits_of_a_row_each(boxed_bed(Moving::side), GetParam(), kSide);  // a row of the top layers at least
}

TEST_P(SurfaceRows, GiveTheBitsOfARowForEveryParticleAsAMeshComesDown) {
  expect_the_bits_of_a_row_each(boxed_bed(Moving::mesh_lid), GetParam(), 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, SurfaceRows, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
