#include <gtest/gtest.h>

#include <cmath>

#include "walls/wall.hpp"
#include "walls/wall_geometry.hpp"
#include "walls/wall_motion.hpp"

namespace gs {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTol = 1e-12;

#define EXPECT_VEC_NEAR(actual, ex, ey, ez)      \
  do {                                           \
    const Vec3d a_ = (actual);                   \
    EXPECT_NEAR(a_.x, (ex), kTol) << #actual;    \
    EXPECT_NEAR(a_.y, (ey), kTol) << #actual;    \
    EXPECT_NEAR(a_.z, (ez), kTol) << #actual;    \
  } while (0)

Wall make_plane(Vec3d point, Vec3d normal) {
  Wall w;
  w.kind = WallKind::plane;
  w.point = point;
  w.normal = normal;
  return w;
}

Wall make_cylinder(Vec3d base, Vec3d axis, double radius, double length) {
  Wall w;
  w.kind = WallKind::cylinder;
  w.point = base;
  w.normal = axis;
  w.radius = radius;
  w.length = length;
  return w;
}

TEST(WallGeometry, PlaneAxisAligned) {
  const Wall w = make_plane({0, 0, 1}, {0, 0, 1});
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {3, 4, 1.2}, 0.5, c));
  EXPECT_NEAR(c.overlap, 0.3, kTol);
  EXPECT_VEC_NEAR(c.normal, 0, 0, 1);
  EXPECT_VEC_NEAR(c.point, 3, 4, 1);
  EXPECT_VEC_NEAR(c.wall_velocity, 0, 0, 0);

  EXPECT_FALSE(wall_contact(w, {3, 4, 1.5}, 0.5, c));  // just touching
  EXPECT_FALSE(wall_contact(w, {3, 4, 2.0}, 0.5, c));
}

TEST(WallGeometry, PlaneFacingDownward) {
  // Ceiling at z = 2, particles below it.
  const Wall w = make_plane({7, -1, 2}, {0, 0, -1});
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {0, 0, 1.9}, 0.25, c));
  EXPECT_NEAR(c.overlap, 0.15, kTol);
  EXPECT_VEC_NEAR(c.normal, 0, 0, -1);
  EXPECT_VEC_NEAR(c.point, 0, 0, 2);
}

TEST(WallGeometry, PlaneOblique) {
  // Plane x + y = 1 with normal (1,1,0)/sqrt2; centre (1,1,0) is 1/sqrt2 in front.
  const double h = 1.0 / std::sqrt(2.0);
  const Wall w = make_plane({1, 0, 0}, {h, h, 0});
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {1, 1, 0}, 1.0, c));
  EXPECT_NEAR(c.overlap, 1.0 - 0.70710678118654752, kTol);
  EXPECT_VEC_NEAR(c.normal, h, h, 0);
  EXPECT_VEC_NEAR(c.point, 0.5, 0.5, 0);
}

TEST(WallGeometry, PlaneManyOrientations) {
  const Vec3d normals[] = {{1, 0, 0}, {0, -1, 0}, {0.6, 0, 0.8}, {2, -3, 6}, {-1, -1, -1}};
  const Vec3d point(0.3, -0.2, 1.1);
  const double r = 0.4;
  for (Vec3d n : normals) {
    n = n * (1.0 / norm(n));
    const Wall w = make_plane(point, n);
    // An in-plane offset: the contact point must follow it, the overlap not.
    Vec3d t = cross(n, Vec3d(0.3, 0.7, -0.2));
    for (double d : {0.35, 0.1, -0.1, -0.39}) {
      WallContact c{};
      ASSERT_TRUE(wall_contact(w, point + t + d * n, r, c)) << d;
      EXPECT_NEAR(c.overlap, r - d, kTol);
      EXPECT_VEC_NEAR(c.normal, n.x, n.y, n.z);
      const Vec3d p = point + t;
      EXPECT_VEC_NEAR(c.point, p.x, p.y, p.z);
    }
    WallContact c{};
    EXPECT_FALSE(wall_contact(w, point + t + 0.41 * n, r, c));   // in front, apart
    EXPECT_FALSE(wall_contact(w, point + t - 0.41 * n, r, c));   // fully behind
  }
}

TEST(WallGeometry, DiskInsideAndOutsideRadius) {
  Wall w = make_plane({0, 0, 0}, {0, 0, 1});
  w.kind = WallKind::disk;
  w.radius = 1.0;
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {0.9, 0, 0.05}, 0.1, c));
  EXPECT_NEAR(c.overlap, 0.05, kTol);
  EXPECT_VEC_NEAR(c.normal, 0, 0, 1);
  EXPECT_VEC_NEAR(c.point, 0.9, 0, 0);

  ASSERT_TRUE(wall_contact(w, {-0.6, 0.79, 0.05}, 0.1, c));  // rho = 0.99
  EXPECT_FALSE(wall_contact(w, {-0.6, 0.81, 0.05}, 0.1, c));  // rho = 1.0081
  EXPECT_FALSE(wall_contact(w, {1.1, 0, 0.05}, 0.1, c));
  // Rim edge is not a contact: centre just beyond the rim, sphere overlapping the rim.
  EXPECT_FALSE(wall_contact(w, {1.05, 0, 0.0}, 0.1, c));
}

TEST(WallGeometry, DiskOffCentreTilted) {
  // Disk centred at (2,0,0) facing -x, radius 0.5.
  Wall w = make_plane({2, 0, 0}, {-1, 0, 0});
  w.kind = WallKind::disk;
  w.radius = 0.5;
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {1.95, 0.3, -0.3}, 0.1, c));  // rho = 0.424
  EXPECT_NEAR(c.overlap, 0.05, kTol);
  EXPECT_VEC_NEAR(c.normal, -1, 0, 0);
  EXPECT_VEC_NEAR(c.point, 2, 0.3, -0.3);
  EXPECT_FALSE(wall_contact(w, {1.95, 0.4, -0.4}, 0.1, c));  // rho = 0.566
}

TEST(WallGeometry, CylinderInsideContact) {
  const Wall w = make_cylinder({0, 0, 0}, {0, 0, 1}, 1.0, 2.0);
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {0.95, 0, 1}, 0.1, c));
  EXPECT_NEAR(c.overlap, 0.05, kTol);
  EXPECT_VEC_NEAR(c.normal, -1, 0, 0);
  EXPECT_VEC_NEAR(c.point, 1, 0, 1);

  // Off-axis direction (0.6, 0.8): normal points back towards the axis.
  ASSERT_TRUE(wall_contact(w, {0.6 * 0.97, 0.8 * 0.97, 0.3}, 0.05, c));
  EXPECT_NEAR(c.overlap, 0.02, kTol);
  EXPECT_VEC_NEAR(c.normal, -0.6, -0.8, 0);
  EXPECT_VEC_NEAR(c.point, 0.6, 0.8, 0.3);

  // Centre slightly outside the wall (within a radius): still pushed inward.
  ASSERT_TRUE(wall_contact(w, {0, -1.02, 1}, 0.1, c));
  EXPECT_NEAR(c.overlap, 0.12, kTol);
  EXPECT_VEC_NEAR(c.normal, 0, 1, 0);

  EXPECT_FALSE(wall_contact(w, {0.5, 0, 1}, 0.1, c));   // well inside
  EXPECT_FALSE(wall_contact(w, {0, 0, 1}, 0.1, c));     // on the axis
  EXPECT_FALSE(wall_contact(w, {1.2, 0, 1}, 0.1, c));   // fully outside
}

TEST(WallGeometry, CylinderAxialLimits) {
  const Wall w = make_cylinder({0, 0, 0}, {0, 0, 1}, 1.0, 2.0);
  WallContact c{};
  EXPECT_TRUE(wall_contact(w, {0.95, 0, 0.0}, 0.1, c));
  EXPECT_TRUE(wall_contact(w, {0.95, 0, 2.0}, 0.1, c));
  EXPECT_FALSE(wall_contact(w, {0.95, 0, -0.01}, 0.1, c));
  EXPECT_FALSE(wall_contact(w, {0.95, 0, 2.01}, 0.1, c));
}

TEST(WallGeometry, CylinderNonAlignedAxis) {
  // Axis along -x from base (1,2,3): axial coordinate of x = 0.5 is 0.5.
  const Wall w = make_cylinder({1, 2, 3}, {-1, 0, 0}, 1.0, 1.0);
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {0.5, 2, 3.95}, 0.1, c));
  EXPECT_NEAR(c.overlap, 0.05, kTol);
  EXPECT_VEC_NEAR(c.normal, 0, 0, -1);
  EXPECT_VEC_NEAR(c.point, 0.5, 2, 4);
  EXPECT_FALSE(wall_contact(w, {1.5, 2, 3.95}, 0.1, c));  // behind the base
}

TEST(WallMotion, TranslatedPlaneShiftsOverlap) {
  Wall w = make_plane({0, 0, 0}, {0, 0, 1});
  w.velocity = Vec3d(0.3, 0, 0.1);
  update_wall_pose(w, 2.0);
  EXPECT_VEC_NEAR(w.shift, 0.6, 0, 0.2);
  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {1, 1, 0.25}, 0.1, c));
  EXPECT_NEAR(c.overlap, 0.05, kTol);  // wall now at z = 0.2
  EXPECT_VEC_NEAR(c.normal, 0, 0, 1);
  EXPECT_VEC_NEAR(c.point, 1, 1, 0.2);
  EXPECT_VEC_NEAR(c.wall_velocity, 0.3, 0, 0.1);
  EXPECT_FALSE(wall_contact(w, {1, 1, 0.31}, 0.1, c));
}

TEST(WallMotion, RotatingCylinderSurfaceVelocity) {
  // Drum about its own axis (parallel to z through (2,3,0)), 60 rpm, R = 0.5.
  const double rpm = 60.0, R = 0.5;
  const double omega = rpm * 2 * kPi / 60;
  Wall w = make_cylinder({2, 3, 0}, {0, 0, 1}, R, 1.0);
  w.axis_point = Vec3d(2, 3, 0);
  w.angular_velocity = Vec3d(0, 0, omega);
  update_wall_pose(w, 0.3);  // an arbitrary angle: the drum looks the same

  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {2.45, 3, 0.5}, 0.1, c));
  EXPECT_NEAR(c.overlap, 0.05, kTol);
  EXPECT_VEC_NEAR(c.normal, -1, 0, 0);
  EXPECT_VEC_NEAR(c.point, 2.5, 3, 0.5);
  // Counter-clockwise about +z: at the +x side the surface moves along +y.
  EXPECT_VEC_NEAR(c.wall_velocity, 0, omega * R, 0);
  EXPECT_NEAR(norm(c.wall_velocity), kPi, kTol);  // 2 pi rad/s * 0.5 m
  EXPECT_NEAR(dot(c.wall_velocity, c.normal), 0.0, kTol);

  // Another point of the surface: at direction (0,-1) the velocity is +x.
  ASSERT_TRUE(wall_contact(w, {2, 2.55, 0.7}, 0.1, c));
  EXPECT_VEC_NEAR(c.point, 2, 2.5, 0.7);
  EXPECT_VEC_NEAR(c.wall_velocity, omega * R, 0, 0);
}

TEST(WallMotion, PlaneRotatedQuarterTurnAboutAxisPoint) {
  // Plane x = 1 facing +x, rotated +90 deg about z through (2,0,0):
  // normal -> +y, point (1,0,0) -> (2,-1,0): world plane y = -1 facing +y.
  Wall w = make_plane({1, 0, 0}, {1, 0, 0});
  w.axis_point = Vec3d(2, 0, 0);
  w.angular_velocity = Vec3d(0, 0, kPi / 2);
  update_wall_pose(w, 1.0);

  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {5, -0.9, 7}, 0.2, c));
  EXPECT_NEAR(c.overlap, 0.1, kTol);
  EXPECT_VEC_NEAR(c.normal, 0, 1, 0);
  EXPECT_VEC_NEAR(c.point, 5, -1, 7);
  // omega x (point - axis_point) = (0,0,pi/2) x (3,-1,7).
  EXPECT_VEC_NEAR(c.wall_velocity, kPi / 2, 3 * kPi / 2, 0);
  EXPECT_FALSE(wall_contact(w, {5, 0.5, 7}, 0.2, c));
}

TEST(WallMotion, RotationCentreTravelsWithShift) {
  // As above plus a translation at (1,0,0): after 1 s the rotation centre is
  // at (3,0,0) and the plane, still y = -1, moves with both motions.
  Wall w = make_plane({1, 0, 0}, {1, 0, 0});
  w.axis_point = Vec3d(2, 0, 0);
  w.angular_velocity = Vec3d(0, 0, kPi / 2);
  w.velocity = Vec3d(1, 0, 0);
  update_wall_pose(w, 1.0);

  WallContact c{};
  ASSERT_TRUE(wall_contact(w, {5, -0.9, 7}, 0.2, c));
  EXPECT_NEAR(c.overlap, 0.1, kTol);
  EXPECT_VEC_NEAR(c.normal, 0, 1, 0);
  EXPECT_VEC_NEAR(c.point, 5, -1, 7);
  // v + omega x (point - (3,0,0)) = (1,0,0) + (0,0,pi/2) x (2,-1,7).
  EXPECT_VEC_NEAR(c.wall_velocity, 1 + kPi / 2, kPi, 0);
}

TEST(WallMotion, RotationAboutZMatchesTextbookMatrix) {
  Wall w;
  w.angular_velocity = Vec3d(0, 0, 0.7);
  update_wall_pose(w, 1.3);
  const double t = 0.91, c = std::cos(t), s = std::sin(t);
  const double expected[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(w.rotation[i], expected[i], kTol) << i;
}

TEST(WallMotion, ZeroAngularVelocityIsIdentity) {
  Wall w;
  w.rotation[1] = 5;  // stale value must be overwritten
  w.velocity = Vec3d(1, -2, 3);
  update_wall_pose(w, 0.5);
  const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(w.rotation[i], identity[i]) << i;
  EXPECT_VEC_NEAR(w.shift, 0.5, -1, 1.5);
}

TEST(WallMotion, PoseComposesOverTime) {
  Wall w1, w2, w12;
  const Vec3d omega(1.0, 2.0, -0.5);
  w1.angular_velocity = w2.angular_velocity = w12.angular_velocity = omega;
  const double t1 = 0.37, t2 = 1.91;
  update_wall_pose(w1, t1);
  update_wall_pose(w2, t2);
  update_wall_pose(w12, t1 + t2);

  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double prod = 0, gram = 0;
      for (int k = 0; k < 3; ++k) {
        prod += w1.rotation[3 * i + k] * w2.rotation[3 * k + j];
        gram += w12.rotation[3 * k + i] * w12.rotation[3 * k + j];
      }
      EXPECT_NEAR(w12.rotation[3 * i + j], prod, kTol) << i << j;
      EXPECT_NEAR(gram, i == j ? 1.0 : 0.0, kTol) << i << j;  // orthonormal
    }
  }
  // The rotation axis is left in place.
  Wall probe = w12;
  EXPECT_VEC_NEAR(wall_rotate(probe, omega), omega.x, omega.y, omega.z);
  // Rotating by the full angle moves a perpendicular vector by that angle.
  const Vec3d k = omega * (1.0 / norm(omega));
  const Vec3d u = cross(k, Vec3d(1, 0, 0));
  const Vec3d ru = wall_rotate(probe, u);
  EXPECT_NEAR(dot(ru, u) / norm2(u), std::cos(norm(omega) * (t1 + t2)), kTol);
  EXPECT_NEAR(dot(cross(u, ru), k) / norm2(u), std::sin(norm(omega) * (t1 + t2)), kTol);
}

TEST(WallMotion, ReferenceAndWorldRoundTrip) {
  Wall w;
  w.axis_point = Vec3d(0.4, -1, 2);
  w.angular_velocity = Vec3d(-0.3, 0.8, 1.1);
  w.velocity = Vec3d(0.2, 0.1, -0.7);
  update_wall_pose(w, 4.2);
  const Vec3d x(1.5, -2.5, 0.25);
  const Vec3d back = wall_to_world(w, wall_to_reference(w, x));
  EXPECT_VEC_NEAR(back, x.x, x.y, x.z);
}

}  // namespace
}  // namespace gs
