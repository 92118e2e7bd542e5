// The analytic walls drawn for viewers: each vertex of a wall's surface lies
// on the analytic surface at the wall's current pose (computed here from the
// pose by hand, not through src/walls), and the triangles cover it: a plane's
// polygon has the area of the plane's cut through the domain box.
#include <gtest/gtest.h>

#include <cmath>

#include "io/h5_snapshot.hpp"
#include "io/wall_surfaces.hpp"
#include "io_test_helpers.hpp"

namespace gs {
namespace {

using test::ScratchDir;

const DomainBox kUnitBox{{0, 0, 0}, {1, 1, 1}};

// x_world = R (x - axis_point) + axis_point + shift, R row-major.
Vec3d posed(const Wall& w, const Vec3d& x) {
  const Vec3d d = x - w.axis_point;
  const double* R = w.rotation;
  return Vec3d(R[0] * d.x + R[1] * d.y + R[2] * d.z, R[3] * d.x + R[4] * d.y + R[5] * d.z,
               R[6] * d.x + R[7] * d.y + R[8] * d.z) +
         w.axis_point + w.shift;
}
Vec3d turned(const Wall& w, const Vec3d& v) { return posed(w, v + w.axis_point) - w.axis_point - w.shift; }

double area(const WallSurface& s) {
  double a = 0;
  for (const auto& t : s.triangles)
    a += 0.5 * norm(cross(s.vertices[t[1]] - s.vertices[t[0]], s.vertices[t[2]] - s.vertices[t[0]]));
  return a;
}

Wall plane(const Vec3d& point, const Vec3d& normal) {
  Wall w;
  w.kind = WallKind::plane;
  w.point = point;
  w.normal = normal * (1.0 / norm(normal));
  return w;
}

void expect_on_plane(const WallSurface& s, const Vec3d& p, const Vec3d& n) {
  ASSERT_GE(s.vertices.size(), 3u);
  for (const Vec3d& x : s.vertices) EXPECT_NEAR(dot(x - p, n), 0.0, 1e-14) << x.x << " " << x.y << " " << x.z;
}

void expect_inside(const WallSurface& s, const DomainBox& b) {
  for (const Vec3d& x : s.vertices) {
    EXPECT_GE(x.x, b.min.x - 1e-14);
    EXPECT_LE(x.x, b.max.x + 1e-14);
    EXPECT_GE(x.y, b.min.y - 1e-14);
    EXPECT_LE(x.y, b.max.y + 1e-14);
    EXPECT_GE(x.z, b.min.z - 1e-14);
    EXPECT_LE(x.z, b.max.z + 1e-14);
  }
}

TEST(WallSurface, PlaneOnABoxFaceIsThatFace) {
  const WallSurface s = wall_surface(plane({0, 0, 0}, {0, 0, 1}), kUnitBox);
  expect_on_plane(s, {0, 0, 0}, {0, 0, 1});
  expect_inside(s, kUnitBox);
  EXPECT_EQ(s.vertices.size(), 4u);
  EXPECT_NEAR(area(s), 1.0, 1e-14);
}

// The plane through the cube's centre normal to its diagonal cuts a regular
// hexagon of side sqrt(2)/2: area 3 sqrt(3)/4.
TEST(WallSurface, PlaneAcrossTheBoxIsItsCut) {
  const Vec3d n = Vec3d(1, 1, 1) * (1 / std::sqrt(3.0));
  const WallSurface s = wall_surface(plane({0.5, 0.5, 0.5}, n), kUnitBox);
  expect_on_plane(s, {0.5, 0.5, 0.5}, n);
  expect_inside(s, kUnitBox);
  EXPECT_EQ(s.vertices.size(), 6u);
  EXPECT_NEAR(area(s), 3 * std::sqrt(3.0) / 4, 1e-12);
  // A slanted cut through four faces: x + z = 1 gives a rectangle 1 by sqrt(2).
  const Vec3d m = Vec3d(1, 0, 1) * (1 / std::sqrt(2.0));
  const WallSurface r = wall_surface(plane({0.5, 0, 0.5}, m), kUnitBox);
  expect_on_plane(r, {0.5, 0, 0.5}, m);
  EXPECT_NEAR(area(r), std::sqrt(2.0), 1e-12);
}

TEST(WallSurface, PlaneMissingTheBoxIsASquareAsWideAsTheDiagonal) {
  const WallSurface s = wall_surface(plane({0, 0, 5}, {0, 0, -1}), kUnitBox);
  expect_on_plane(s, {0, 0, 5}, {0, 0, -1});
  EXPECT_NEAR(area(s), 3.0, 1e-12);  // (sqrt 3)^2
}

// A moved plane is drawn where it is now: rotated about axis_point and shifted.
TEST(WallSurface, MovedPlaneIsDrawnAtItsCurrentPose) {
  Wall w = plane({0, 0, 0.2}, {0, 0, 1});
  w.axis_point = {0.5, 0.5, 0.5};
  const double c = std::cos(0.3), s = std::sin(0.3);  // about x
  const double r[9] = {1, 0, 0, 0, c, -s, 0, s, c};
  for (int k = 0; k < 9; ++k) w.rotation[k] = r[k];
  w.shift = {0, 0, 0.1};
  const WallSurface surface = wall_surface(w, kUnitBox);
  expect_on_plane(surface, posed(w, w.point), turned(w, w.normal));
  expect_inside(surface, kUnitBox);
}

TEST(WallSurface, CylinderVerticesLieOnItsSurface) {
  const Wall drum = test::sample_walls()[1];  // rotated about y and shifted
  const WallSurface s = wall_surface(drum, kUnitBox);
  const Vec3d base = posed(drum, drum.point), axis = turned(drum, drum.normal);
  ASSERT_EQ(s.vertices.size(), 2u * kWallSurfaceSegments);
  double lowest = 1, highest = -1;
  for (const Vec3d& x : s.vertices) {
    const double along = dot(x - base, axis);
    const double rho = norm(x - base - along * axis);
    EXPECT_NEAR(rho, drum.radius, 1e-14);
    lowest = std::min(lowest, along);
    highest = std::max(highest, along);
  }
  EXPECT_NEAR(lowest, 0.0, 1e-15);
  EXPECT_NEAR(highest, drum.length, 1e-15);
  // The band of S chords: 2 R L S sin(pi / S).
  const double S = kWallSurfaceSegments;
  EXPECT_NEAR(area(s), 2 * drum.radius * drum.length * S * std::sin(M_PI / S), 1e-14);
}

TEST(WallSurface, DiskVerticesLieOnItsPlaneWithinItsRadius) {
  Wall disk;
  disk.kind = WallKind::disk;
  disk.point = {0.3, 0.4, 0.5};
  disk.normal = Vec3d(0, 0.6, 0.8);
  disk.radius = 0.25;
  disk.shift = {0.01, 0.02, 0.03};
  const WallSurface s = wall_surface(disk, kUnitBox);
  const Vec3d centre = posed(disk, disk.point);
  expect_on_plane(s, centre, disk.normal);
  int on_rim = 0;
  for (const Vec3d& x : s.vertices) {
    EXPECT_LE(norm(x - centre), disk.radius * (1 + 1e-15));
    on_rim += std::abs(norm(x - centre) - disk.radius) < 1e-14;
  }
  EXPECT_EQ(on_rim, kWallSurfaceSegments);
  const double S = kWallSurfaceSegments;
  EXPECT_NEAR(area(s), 0.5 * S * disk.radius * disk.radius * std::sin(2 * M_PI / S), 1e-14);
}

// The snapshot stores each wall's surface as the reader computes it, named as in the scene.
TEST(WallSurface, SnapshotHoldsTheSurfacesWhenGivenTheDomain) {
  ScratchDir dir;
  const std::vector<Wall> walls = test::sample_walls();
  SnapshotMetadata m;
  m.wall_names = {"floor", "drum"};
  m.domain = DomainBox{{-0.2, -0.1, -0.1}, {0.2, 0.1, 0.3}};
  const std::string path = dir.file("s.h5");
  write_snapshot(path, test::sample_particles(3), default_snapshot_fields(), walls, m);
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const std::string g = "wall_surfaces/" + std::to_string(k);
    const WallSurface expected = wall_surface(walls[k], *m.domain);
    std::vector<hsize_t> dims;
    const auto xyz = test::read_h5<double>(path, g + "/vertices", H5T_NATIVE_DOUBLE, &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{expected.vertices.size(), 3}));
    ASSERT_EQ(xyz.size(), 3 * expected.vertices.size());
    for (std::size_t i = 0; i < expected.vertices.size(); ++i) EXPECT_EQ(xyz[3 * i + 2], expected.vertices[i].z);
    const auto tri = test::read_h5<std::int32_t>(path, g + "/triangles", H5T_NATIVE_INT32, &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{expected.triangles.size(), 3}));
    EXPECT_EQ(test::read_h5_string(path, g, "name"), m.wall_names[k]);
  }
  const std::vector<WallSurfaceInfo> info = read_snapshot_wall_surfaces(path);
  ASSERT_EQ(info.size(), 2u);
  EXPECT_EQ(info[0].name, "floor");
  EXPECT_EQ(info[1].triangles, 2u * kWallSurfaceSegments);
  // Without a domain no surfaces are written.
  write_snapshot(dir.file("plain.h5"), test::sample_particles(3), default_snapshot_fields(), walls, SnapshotMetadata());
  EXPECT_FALSE(test::h5_link_exists(dir.file("plain.h5"), "wall_surfaces"));
  EXPECT_TRUE(read_snapshot_wall_surfaces(dir.file("plain.h5")).empty());
}

}  // namespace
}  // namespace gs
