// Triangle meshes in the force kernel (engine/force_kernel.hpp), on every
// backend: a tessellated floor acts as the analytic plane (above a face, an
// edge or a vertex of the tessellation), a turning disk carries a sphere
// along through friction, and the load a resting bed puts on a mesh floor is
// its weight.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_time.hpp"
#include "mesh_test_helpers.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// R = 2^-10 m is exact in fp32, so the stored radius equals the one used here.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;

double mass() { return stored_sphere_mass(kRadius, kDensity); }

SceneSpec scene_with_gravity() {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
  scene.pairs[0].rolling_friction = 0.2;
  scene.effects = kFriction | kRollingResistance;
  scene.gravity = {0, 0, -kGravity};
  scene.time_step = linear_contact_time(kStiffness, mass(), kRestitution) / 50;
  scene.domain_min = {-0.02, -0.02, -0.003};  // thin: few cells to list each step
  scene.domain_max = {0.02, 0.02, 0.005};
  return scene;
}

// An 8 x 8 jittered square floor at z = 0, centred on the origin, 1 mm cells.
FlatSquare floor_square() {
  return make_flat_square(8, 0.001, 0.2, Rotation(Vec3d(0, 0, 1), 0), Vec3d(-0.004, -0.004, 0), 7);
}

class MeshEngineTest : public testing::TestWithParam<Backend> {};

// Dropped from 0.2 R above touching, a sphere bounces and comes to rest; on
// the tessellated floor it must follow the plane run step by step, whether it
// lands inside a face, exactly on an edge or exactly on a vertex (where six
// triangles meet and the rule must give one contact).
TEST_P(MeshEngineTest, TessellatedFloorActsAsPlane) {
  const FlatSquare sq = floor_square();
  // An interior triangle: its centroid, the midpoint of its first edge, its first corner.
  const TriangleIndices& t = sq.mesh.triangles[2 * (3 * 8 + 3)];
  const Vec3d a = sq.local[t[0]], b = sq.local[t[1]], c = sq.local[t[2]];
  const struct {
    const char* where;
    Vec3d local;
  } cases[] = {{"face", (a + b + c) * (1.0 / 3)}, {"edge", (a + b) * 0.5}, {"vertex", a}};
  for (const auto& k : cases) {
    SCOPED_TRACE(k.where);
    const Vec3d start = sq.to_world(k.local) + Vec3d(0, 0, 1.2 * kRadius);
    SceneSpec plane = scene_with_gravity();
    plane.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
    plane.particles = {particle(0, kRadius, start)};
    SceneSpec mesh = scene_with_gravity();
    add_mesh(mesh.meshes, sq.mesh);
    mesh.particles = plane.particles;
    Simulation on_plane(plane, {GetParam()}), on_mesh(mesh, {GetParam()});
    double max_gap = 0;
    for (int chunk = 0; chunk < 40; ++chunk) {  // 0.026 s: the bounce and the rest
      on_plane.run(100);
      on_mesh.run(100);
      const ParticleSnapshot p = on_plane.snapshot(), m = on_mesh.snapshot();
      max_gap = std::max(max_gap, norm(p.position[0] - m.position[0]));
    }
    const ParticleSnapshot p = on_plane.snapshot(), m = on_mesh.snapshot();
    // The static overlap m g / k is 1e-7 m; the contact is the plane's to rounding.
    EXPECT_LT(max_gap, 1e-15) << "largest position difference";
    EXPECT_NEAR(m.force[0].z, p.force[0].z, 1e-12 * mass() * kGravity);
    EXPECT_NEAR(m.position[0].z, kRadius - mass() * kGravity / kStiffness, 1e-3 * mass() * kGravity / kStiffness);
    ASSERT_EQ(on_mesh.mesh_loads().size(), 1u);
    EXPECT_NEAR(on_mesh.mesh_loads()[0].force.z, -m.force[0].z, 1e-12 * mass() * kGravity);
  }
}

// A sphere rolling without slipping down a slope (gravity tilted by 10 deg)
// crosses faces, edges and vertices of the tessellated floor: its friction
// spring must carry over from feature to feature as it does on the plane, so
// the two runs agree, and both roll at a = 5/7 g sin(theta).
TEST_P(MeshEngineTest, RollsAcrossFacetsAsOnPlane) {
  const double theta = 10 * M_PI / 180;
  SceneSpec plane = scene_with_gravity();
  plane.effects = kFriction;
  plane.pairs[0].rolling_friction = 0;
  plane.gravity = {kGravity * std::sin(theta), 0, -kGravity * std::cos(theta)};
  const Vec3d start(-0.0035, 0.0003, kRadius - mass() * kGravity * std::cos(theta) / kStiffness);
  plane.particles = {particle(0, kRadius, start)};
  SceneSpec mesh = plane;
  plane.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  add_mesh(mesh.meshes, floor_square().mesh);
  Simulation on_plane(plane, {GetParam()}), on_mesh(mesh, {GetParam()});
  const int steps = int(0.09 / plane.time_step);
  double max_gap = 0;
  for (int done = 0; done < steps; done += 200) {
    on_plane.run(200);
    on_mesh.run(200);
    max_gap = std::max(max_gap, norm(on_plane.snapshot().position[0] - on_mesh.snapshot().position[0]));
  }
  const double t = on_plane.time(), travelled = on_plane.snapshot().position[0].x - start.x;
  EXPECT_GT(travelled, 0.004) << "the sphere should cross several facets";
  EXPECT_NEAR(travelled, 0.5 * 5.0 / 7.0 * kGravity * std::sin(theta) * t * t, 0.02 * travelled);
  EXPECT_LT(max_gap, 1e-12) << "the mesh run left the plane run (a spring lost at a facet boundary)";
}

// A flat disk of radius 2 cm in rings of triangles around its centre.
TriangleMesh disk_mesh(double radius, int rings, int sectors) {
  TriangleMesh mesh;
  mesh.name = "disk";
  mesh.vertices.push_back(Vec3d());
  for (int r = 1; r <= rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2 * M_PI * (s + 0.5 * (r % 2)) / sectors;
      mesh.vertices.push_back(Vec3d(std::cos(phi), std::sin(phi), 0) * (radius * r / rings));
    }
  auto ring = [&](int r, int s) { return std::int32_t(1 + (r - 1) * sectors + (s % sectors)); };
  for (int s = 0; s < sectors; ++s) mesh.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      // Outer ring r + 1 is turned by half a sector against ring r (alternately).
      const int shift = r % 2;  // 1: the outer vertex s sits between inner s and s + 1
      mesh.triangles.push_back({ring(r, s), ring(r + 1, s + 1 - shift), ring(r, s + 1)});
      mesh.triangles.push_back({ring(r + 1, s + shift), ring(r + 1, s + 1 + shift), ring(r, s + shift)});
    }
  return mesh;
}

// A sphere placed at rest on a disk turning at 30 rpm about its normal: sliding
// friction spins it up, rolling resistance stops it rolling relative to the
// disk, and it then turns with the disk: speed Omega r, tangential, at a
// constant radius (the centripetal force m Omega^2 r = 0.1 m g is within the
// friction cap).
TEST_P(MeshEngineTest, TurningDiskCarriesSphere) {
  SceneSpec scene = scene_with_gravity();
  const double rpm = 30, omega = rpm * 2 * M_PI / 60, r0 = 0.01;
  add_mesh(scene.meshes, disk_mesh(0.018, 6, 24), 0, rotation_at_rpm(Vec3d(), Vec3d(0, 0, 1), rpm));
  scene.particles = {particle(0, kRadius, {r0, 0, kRadius - mass() * kGravity / kStiffness})};
  Simulation sim(scene, {GetParam()});
  sim.run(std::llround(0.3 / scene.time_step));  // spin-up
  ParticleSnapshot s = sim.snapshot();
  const double phi0 = std::atan2(s.position[0].y, s.position[0].x), t0 = s.time;
  for (int k = 0; k < 4; ++k) {
    sim.run(std::llround(0.05 / scene.time_step));
    s = sim.snapshot();
    const Vec3d x = s.position[0];
    const double r = std::hypot(x.x, x.y);
    const Vec3d carried = cross(Vec3d(0, 0, omega), Vec3d(x.x, x.y, 0));
    EXPECT_NEAR(norm(s.velocity[0] - carried) / norm(carried), 0, 0.03) << "t = " << s.time;
    EXPECT_NEAR(r, r0, 0.05 * r0) << "t = " << s.time;
  }
  // Angle turned over the last 0.2 s against the disk's, unwrapped (< one turn).
  double turned = std::atan2(s.position[0].y, s.position[0].x) - phi0;
  if (turned < 0) turned += 2 * M_PI;
  EXPECT_NEAR(turned / (omega * (s.time - t0)), 1.0, 0.03);
  // The disk's load: the sphere's weight down, and a torque about z that the
  // rolling sphere's friction exerts (small, but it must stay finite).
  const MeshLoad load = sim.mesh_loads()[0];
  EXPECT_NEAR(load.force.z, -mass() * kGravity, 1e-3 * mass() * kGravity);
  EXPECT_TRUE(std::isfinite(load.torque.z));
}

// Two square-packed layers in a frictionless box of analytic side walls, on a
// mesh floor whose axis point is the origin while the bed is centred at
// (a, b): at rest the floor carries the whole weight W (side walls carry no
// vertical load without friction), and the torque about the origin is that
// of W at the centre of mass, (-b W, a W, 0).
TEST_P(MeshEngineTest, RestingBedLoadsMeshFloorWithItsWeight) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.0);
  scene.gravity = {0, 0, -kGravity};
  scene.time_step = linear_contact_time(kStiffness, mass(), kRestitution) / 50;
  scene.domain_min = {-0.006, -0.008, -0.003};
  scene.domain_max = {0.008, 0.006, 0.008};
  const double a = 0.002, b = -0.001, half = 4 * kRadius;
  add_mesh(scene.meshes, make_flat_square(10, 0.001, 0.2, Rotation(Vec3d(0, 0, 1), 0), Vec3d(-0.003, -0.006, 0), 3).mesh);
  scene.walls = {plane_wall({a - half, 0, 0}, {1, 0, 0}), plane_wall({a + half, 0, 0}, {-1, 0, 0}),
                 plane_wall({0, b - half, 0}, {0, 1, 0}), plane_wall({0, b + half, 0}, {0, -1, 0})};
  ParticleId id = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      scene.particles.push_back(
          particle(id++, kRadius, {a + (2 * i - 3) * kRadius, b + (2 * j - 3) * kRadius, 1.05 * kRadius}));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      scene.particles.push_back(
          particle(id++, kRadius, {a + (2 * i - 2) * kRadius, b + (2 * j - 2) * kRadius, 2.5 * kRadius}));
  Simulation sim(scene, {GetParam()});
  sim.run(std::llround(0.1 / scene.time_step));
  const double weight = double(scene.particles.size()) * mass() * kGravity;
  const MeshLoad load = sim.mesh_loads()[0];
  EXPECT_NEAR(load.force.z / -weight, 1.0, 1e-6);
  EXPECT_NEAR(load.force.x, 0, 1e-9 * weight);
  EXPECT_NEAR(load.force.y, 0, 1e-9 * weight);
  EXPECT_NEAR(load.torque.x / (-b * weight), 1.0, 1e-4);
  EXPECT_NEAR(load.torque.y / (a * weight), 1.0, 1e-4);
  EXPECT_NEAR(load.torque.z, 0, 1e-9 * weight * kRadius);
}

INSTANTIATE_TEST_SUITE_P(Backends, MeshEngineTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
