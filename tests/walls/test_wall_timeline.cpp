// Wall timelines (walls/timeline.hpp, wall_at): the pose of a wall moved by a
// velocity table is the exact integral of the piecewise-linear velocity, a
// turning wall's angle that of its rpm table, an oscillating wall sits at
// A sin(2 pi f t + phase); the velocity at a contact point is the time
// derivative of the pose, and the active window switches contacts off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "walls/mesh_motion.hpp"
#include "walls/wall_geometry.hpp"
#include "walls/wall_motion.hpp"

namespace gs {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

// Independent of the code under test: the integral of the line through
// (t0, v0), (t1, v1) from t0 to min(t, t1), segment by segment.
double trapezoid_integral(const std::vector<double>& t, const std::vector<double>& v, double until) {
  double sum = 0;
  for (std::size_t k = 0; k + 1 < t.size() && t[k] < until; ++k) {
    const double b = std::min(until, t[k + 1]);
    const double vb = v[k] + (v[k + 1] - v[k]) * (b - t[k]) / (t[k + 1] - t[k]);
    sum += (b - t[k]) * (v[k] + vb) / 2;
  }
  if (until > t.back()) sum += (until - t.back()) * v.back();
  return sum;
}

Wall floor_wall() {
  Wall w;
  w.point = Vec3d(0, 0, 0);
  w.normal = Vec3d(0, 0, 1);
  return w;
}

TEST(WallTimeline, VelocityTableIntegratesExactly) {
  const std::vector<double> t = {0, 0.25, 0.5, 1.25, 2.0};
  const std::vector<double> vz = {0, 0.4, 0.4, -0.3, 0.1};
  std::vector<Vec3d> v;
  for (double x : vz) v.push_back(Vec3d(0.5 * x, 0, x));
  Timeline tl;
  tl.velocity = make_rate_table(t, v);
  Wall prescribed = floor_wall();
  prescribed.motion_start = 0.1;  // the table's clock starts with the motion
  for (int k = 0; k <= 400; ++k) {
    const double time = 0.00731 * k;  // over every segment, and past the last time
    const double tau = std::max(0.0, time - 0.1);
    const Wall w = wall_at(prescribed, tl, time);
    const double z = trapezoid_integral(t, vz, tau);
    EXPECT_NEAR(w.shift.z, z, 1e-15) << "t = " << time;
    EXPECT_NEAR(w.shift.x, 0.5 * z, 1e-15) << "t = " << time;
    // The velocity is the table's (zero before the motion starts) and the pose's derivative.
    const double h = 1e-7;
    const double dzdt = (wall_at(prescribed, tl, time + h).shift.z - wall_at(prescribed, tl, time - h).shift.z) / (2 * h);
    if (time > 0.1 + h) {
      EXPECT_NEAR(w.velocity.z, dzdt, 1e-7) << "t = " << time;
    }
    if (time < 0.1) {
      EXPECT_EQ(w.velocity.z, 0.0);
    }
    // The contact of a sphere sees that velocity as the wall's.
    WallContact c;
    ASSERT_TRUE(wall_contact(w, Vec3d(0.01, 0.02, w.shift.z + 0.0005), 0.001, c));
    EXPECT_EQ(c.wall_velocity.z, w.velocity.z);
  }
}

TEST(WallTimeline, RpmTableTurnsByItsIntegral) {
  // A drum that spins up linearly to 30 rpm in 2 s, holds, then slows to 10 rpm.
  const std::vector<double> t = {0, 2, 5, 6};
  const std::vector<double> rpm = {0, 30, 30, 10};
  std::vector<Vec3d> omega;
  const Vec3d axis = Vec3d(1, 2, 2) * (1.0 / 3);
  for (double r : rpm) omega.push_back(axis * (r * kTwoPi / 60));
  MeshMotion m;
  m.axis_point = Vec3d(0.1, 0, -0.2);
  m.timeline.angular_velocity = make_rate_table(t, omega);
  const Vec3d x_ref(0.3, -0.1, 0.4);
  for (double time : {0.0, 0.7, 2.0, 3.3, 5.5, 6.0, 9.1}) {
    const double angle = trapezoid_integral(t, rpm, time) * kTwoPi / 60;
    // Rodrigues by hand: x = c + (r cos a + (k x r) sin a + k (k.r)(1 - cos a)).
    const Vec3d r = x_ref - m.axis_point;
    const Vec3d expected = m.axis_point + r * std::cos(angle) + cross(axis, r) * std::sin(angle) +
                           axis * (dot(axis, r) * (1 - std::cos(angle)));
    const MeshPose p = mesh_pose(m, time);
    const Vec3d x = pose_point(p, x_ref);
    EXPECT_NEAR(norm(x - expected), 0, 1e-14) << "t = " << time;
    // Velocity of the material point: the derivative of its position (off
    // the table's times, where the rate has a kink).
    const double h = 1e-6;
    if (std::find(t.begin(), t.end(), time) != t.end()) continue;
    const Vec3d dxdt = (pose_point(mesh_pose(m, time + h), x_ref) - pose_point(mesh_pose(m, time - h), x_ref)) * (0.5 / h);
    if (time > h) {
      EXPECT_NEAR(norm(mesh_point_velocity(p, x) - dxdt), 0, 1e-8) << "t = " << time;
    }
  }
}

TEST(WallTimeline, OscillationIsASine) {
  Timeline tl;
  const double A = 0.002, f = 15, phase = 0.3;
  tl.oscillation.amplitude = Vec3d(0, 0, A);
  tl.oscillation.frequency = f;
  tl.oscillation.phase = phase;
  const Wall prescribed = floor_wall();
  for (int k = 0; k < 200; ++k) {
    const double time = 0.0013 * k;
    const Wall w = wall_at(prescribed, tl, time);
    EXPECT_NEAR(w.shift.z, A * std::sin(kTwoPi * f * time + phase), 1e-17);
    EXPECT_NEAR(w.velocity.z, A * kTwoPi * f * std::cos(kTwoPi * f * time + phase), 1e-15);
    EXPECT_EQ(w.shift.x, 0.0);
  }
}

TEST(WallTimeline, InactiveWallTouchesNothing) {
  Timeline tl;
  tl.active.from = 0.2;
  tl.active.until = 0.5;
  const Wall prescribed = floor_wall();
  WallContact c;
  const Vec3d x(0, 0, 0.0009);  // overlaps the floor by 0.1 mm
  EXPECT_FALSE(wall_contact(wall_at(prescribed, tl, 0.1), x, 0.001, c));
  EXPECT_TRUE(wall_contact(wall_at(prescribed, tl, 0.2), x, 0.001, c));
  EXPECT_TRUE(wall_contact(wall_at(prescribed, tl, 0.4999), x, 0.001, c));
  EXPECT_FALSE(wall_contact(wall_at(prescribed, tl, 0.5), x, 0.001, c));
  MeshMotion m;
  m.timeline = tl;
  EXPECT_FALSE(mesh_pose(m, 0.1).active);
  EXPECT_TRUE(mesh_pose(m, 0.3).active);
  EXPECT_FALSE(mesh_pose(m, 0.6).active);
}

TEST(WallTimeline, TablesAreChecked) {
  EXPECT_THROW(make_rate_table({0, 1, 1}, {Vec3d(), Vec3d(), Vec3d()}), std::invalid_argument);
  EXPECT_THROW(make_rate_table({0.5, 1}, {Vec3d(), Vec3d()}), std::invalid_argument);
  EXPECT_THROW(make_rate_table({0, 1}, {Vec3d()}), std::invalid_argument);
}

}  // namespace
}  // namespace gs
