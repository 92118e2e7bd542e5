// Prescribed mesh motion: poses from the absolute time (no drift, order
// independent), rotation at an rpm about an arbitrary axis, and the velocity of
// the mesh material at a contact point.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh_test_helpers.hpp"
#include "walls/impeller.hpp"

namespace gs {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

TEST(MeshMotion, RpmGivesTheAngularVelocity) {
  const MeshMotion m = rotation_at_rpm(Vec3d(1, 2, 3), Vec3d(0, 0, 2), 30);
  EXPECT_NEAR(m.angular_velocity.z, kTwoPi * 0.5, 1e-15);
  EXPECT_EQ(m.angular_velocity.x, 0);
  EXPECT_THROW(rotation_at_rpm(Vec3d(), Vec3d(), 30), std::invalid_argument);
}

TEST(MeshMotion, QuarterTurnAboutAnOffsetAxis) {
  // 15 rpm about +z through (1, 0, 0): a quarter turn takes one second.
  const MeshPose p = mesh_pose(rotation_at_rpm(Vec3d(1, 0, 0), Vec3d(0, 0, 1), 15), 1.0);
  const Vec3d x = pose_point(p, Vec3d(2, 0, 5));
  EXPECT_NEAR(x.x, 1, 1e-15);
  EXPECT_NEAR(x.y, 1, 1e-15);
  EXPECT_NEAR(x.z, 5, 1e-15);
}

TEST(MeshMotion, PosesComeFromTheAbsoluteTime) {
  MeshSet set;
  add_mesh(set, make_impeller(), 0, rotation_at_rpm(Vec3d(0.001, -0.002, 0), Vec3d(0.1, 0.2, 1), 42.5,
                                                      Vec3d(0.01, 0, -0.003)));
  // After many out-of-order moves, the vertices are those of a direct move.
  for (double t : {3.7, 0.1, 100.25, 1e4, 12.0}) move_meshes(set, t);
  std::vector<Vec3d> after = set.vertex;
  MeshSet fresh;
  add_mesh(fresh, make_impeller(), 0, set.motion[0]);
  move_meshes(fresh, 12.0);
  for (std::size_t v = 0; v < after.size(); ++v) {
    EXPECT_EQ(after[v].x, fresh.vertex[v].x);
    EXPECT_EQ(after[v].y, fresh.vertex[v].y);
    EXPECT_EQ(after[v].z, fresh.vertex[v].z);
  }
  // Whole revolutions bring a rotating mesh back (without translation).
  MeshSet turning;
  add_mesh(turning, make_impeller(), 0, rotation_at_rpm(Vec3d(), Vec3d(0, 0, 1), 30));
  move_meshes(turning, 2.0 * 1000);  // 1000 revolutions
  for (std::size_t v = 0; v < turning.vertex.size(); ++v)
    EXPECT_NEAR(norm(turning.vertex[v] - turning.reference[v]), 0, 1e-13);
}

TEST(MeshMotion, MaterialVelocityIsTheTimeDerivativeOfPosition) {
  const MeshMotion m = rotation_at_rpm(Vec3d(0.3, -0.1, 0.2), Vec3d(1, -2, 0.5), 120, Vec3d(0.2, -0.1, 0.05));
  const Vec3d x_ref(0.04, 0.01, -0.02);
  const double t = 0.731, h = 1e-6;
  const Vec3d dxdt = (pose_point(mesh_pose(m, t + h), x_ref) - pose_point(mesh_pose(m, t - h), x_ref)) * (0.5 / h);
  const Vec3d v = mesh_point_velocity(mesh_pose(m, t), pose_point(mesh_pose(m, t), x_ref));
  EXPECT_NEAR(norm(v - dxdt), 0, 1e-8 * norm(v));
}

TEST(MeshMotion, RestsUntilItsStartThenRunsFromIt) {
  MeshMotion m = rotation_at_rpm(Vec3d(0.3, -0.1, 0.2), Vec3d(1, -2, 0.5), 120, Vec3d(0.2, -0.1, 0.05));
  const MeshMotion from_zero = m;
  m.start = 1.5;
  const Vec3d x_ref(0.04, 0.01, -0.02);
  for (double t : {0.0, 0.7, 1.5}) {
    const MeshPose p = mesh_pose(m, t);
    EXPECT_NEAR(norm(pose_point(p, x_ref) - x_ref), 0, 1e-16) << t;
    // At rest before the start; moving from it on.
    EXPECT_EQ(norm(mesh_point_velocity(p, x_ref)) == 0, t < m.start) << t;
  }
  // After the start: the pose and velocities of a motion begun at 0, 1.5 s later.
  const MeshPose late = mesh_pose(m, 1.5 + 0.731), early = mesh_pose(from_zero, 0.731);
  EXPECT_NEAR(norm(pose_point(late, x_ref) - pose_point(early, x_ref)), 0, 1e-15);
  EXPECT_EQ(norm(late.angular_velocity - from_zero.angular_velocity), 0);
  EXPECT_EQ(norm(late.velocity - from_zero.velocity), 0);
}

TEST(MeshMotion, ContactsCarryTheMaterialVelocity) {
  // A flat square turning about its normal: the contact point moves with it.
  const test::FlatSquare sq = test::make_flat_square(4, 0.25, 0.1, test::Rotation(Vec3d(0, 0, 1), 0), Vec3d(), 6);
  MeshSet set;
  const double rpm = 60;
  add_mesh(set, sq.mesh, 0, rotation_at_rpm(Vec3d(0.5, 0.5, 0), Vec3d(0, 0, 1), rpm));
  move_meshes(set, 0.1);
  const std::vector<MeshContact> c = test::all_contacts(set, Vec3d(0.7, 0.5, 0.1), 0.2);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].wall_velocity.x, 0, 1e-14);
  EXPECT_NEAR(c[0].wall_velocity.y, 0.2 * kTwoPi * rpm / 60, 1e-14);
  EXPECT_NEAR(c[0].wall_velocity.z, 0, 1e-14);
}

}  // namespace
}  // namespace gs
