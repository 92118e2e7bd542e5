// What the surface rows (engine/surface_rows.hpp) rely on: a sphere that
// touches a wall after it and the wall have moved was within reach of the
// wall before (wall_within_reach, walls/wall_geometry.hpp), where the reach
// is the sphere's move plus the bound on the wall's (wall_displacement_bound,
// walls/wall_drift.hpp); and WallDrift calls for a build once a wall has moved
// half a skin or been switched.
#include <gtest/gtest.h>

#include <random>

#include "walls/wall_drift.hpp"
#include "walls/wall_geometry.hpp"
#include "walls/wall_motion.hpp"
#include "wall_test_helpers.hpp"

namespace gs {
namespace {

// A wall of a kind, turning about a tilted axis and drifting.
Wall moving_wall(WallKind kind, Vec3d point, Vec3d normal, double radius = 0, double length = 0) {
  Wall w = make_wall(kind, point, normal, radius, length);
  w.axis_point = {0.3, -0.2, 0.1};
  w.angular_velocity = {0.4, -1.1, 2.3};
  w.velocity = {0.05, 0.02, -0.03};
  return w;
}

Wall posed(Wall w, double t) {
  update_wall_pose(w, t);
  return w;
}

// Spheres scattered about the wall at time t0 move by up to `move`; the wall
// moves from t0 to t1. Every contact at t1 must have been within reach at t0.
void expect_reach_holds_every_contact(const Wall& w, double t0, double t1, double move) {
  const Vec3d lo{-0.1, -0.5, -0.3}, hi{0.7, 0.1, 0.5};
  const Wall before = posed(w, t0), after = posed(w, t1);
  const double drift = wall_displacement_bound(before, after, lo, hi);
  ASSERT_GT(drift, 0);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1), v(-1, 1);
  int contacts = 0, out_of_reach = 0;
  for (int k = 0; k < 40000; ++k) {
    const double radius = 0.005 + 0.01 * u(rng);
    const Vec3d x{lo.x + (hi.x - lo.x) * u(rng), lo.y + (hi.y - lo.y) * u(rng), lo.z + (hi.z - lo.z) * u(rng)};
    Vec3d step{v(rng), v(rng), v(rng)};
    step = step * (move * u(rng) / std::max(norm(step), 1e-12));
    WallContact c;
    const bool within = wall_within_reach(before, x, radius, move + drift);
    if (wall_contact(after, x + step, radius, c)) {
      ++contacts;
      ASSERT_TRUE(within) << "a contact out of reach: overlap " << c.overlap << " at k = " << k;
    }
    out_of_reach += !within;
  }
  EXPECT_GT(contacts, 50);
  EXPECT_GT(out_of_reach, 10000);  // the reach does leave most of the box out
}

TEST(WallReach, HoldsEveryContactOfAMovedWallOfEachKind) {
  Wall plate = moving_wall(WallKind::plate, {0.3, -0.2, 0.1}, {0.2, 1, 0.3}, 0.25);
  plate.hole_half[0] = 0.05;
  Wall cone = moving_wall(WallKind::cone, {0.3, -0.2, -0.1}, {0, 0.2, 1}, 0.25, 0.3);
  cone.end_radius = 0.05;
  const Wall walls[] = {moving_wall(WallKind::plane, {0.3, -0.2, 0.1}, {1, 2, -0.5}),
                        moving_wall(WallKind::disk, {0.3, -0.2, 0.1}, {0, 0.3, 1}, 0.2),
                        moving_wall(WallKind::cylinder, {0.3, -0.2, -0.2}, {0.1, 0, 1}, 0.15, 0.5), plate, cone};
  for (const Wall& w : walls) {
    SCOPED_TRACE(int(w.kind));
    expect_reach_holds_every_contact(w, 0.2, 0.23, 0.004);
    expect_reach_holds_every_contact(w, 1.1, 1.1, 0.01);  // the wall still: the sphere's move alone
  }
}

TEST(WallReach, AnInactiveWallIsOutOfReach) {
  Wall w = moving_wall(WallKind::plane, {0, 0, 0}, {0, 0, 1});
  EXPECT_TRUE(wall_within_reach(w, {0, 0, 0.011}, 0.01, 0.002));
  EXPECT_FALSE(wall_within_reach(w, {0, 0, 0.013}, 0.01, 0.002));
  w.active = false;
  EXPECT_FALSE(wall_within_reach(w, {0, 0, 0.011}, 0.01, 0.002));
}

// A turn by angle a about an axis through c moves a point at distance d from
// the axis by 2 d sin(a / 2); the Frobenius bound is 2 sqrt(2) sin(a / 2)
// times the farthest corner's distance from c, at least that.
TEST(WallDrift, BoundsATurnAndAShift) {
  Wall w = moving_wall(WallKind::plane, {0, 0, 0}, {0, 0, 1});
  w.axis_point = {0, 0, 0};
  w.angular_velocity = {0, 0, 1};
  w.velocity = {0, 0, 0};
  const Vec3d lo{-1, -1, 0}, hi{1, 1, 0};
  const double a = 0.01;
  const double bound = wall_displacement_bound(posed(w, 0), posed(w, a), lo, hi);
  EXPECT_GE(bound, 2 * std::sqrt(2.0) * std::sin(a / 2));  // the corner (1, 1, 0) moves that far
  EXPECT_NEAR(bound, 2 * std::sqrt(2.0) * std::sin(a / 2) * std::sqrt(2.0), 1e-12);
  w.angular_velocity = {0, 0, 0};
  w.velocity = {0.3, 0, -0.4};
  EXPECT_NEAR(wall_displacement_bound(posed(w, 0), posed(w, 2), lo, hi), 1.0, 1e-15);
}

TEST(WallDrift, ABuildIsDueOnceAWallMovedHalfASkinOrWasSwitched) {
  Wall w = moving_wall(WallKind::plane, {0, 0, 0}, {0, 0, 1});
  w.angular_velocity = {0, 0, 0};
  w.velocity = {0, 0, -1};
  WallDrift drift({-1, -1, -1}, {1, 1, 1});
  EXPECT_TRUE(drift.beyond({posed(w, 0)}, 0.05));  // never built
  drift.built({posed(w, 0)});
  EXPECT_FALSE(drift.beyond({posed(w, 0.049)}, 0.05));
  EXPECT_TRUE(drift.beyond({posed(w, 0.051)}, 0.05));
  Wall off = posed(w, 0);
  off.active = false;
  EXPECT_TRUE(drift.beyond({off}, 0.05));
  EXPECT_TRUE(drift.beyond({posed(w, 0), posed(w, 0)}, 0.05));  // another wall
}

}  // namespace
}  // namespace gs
