// The force loop's first test of a wall (walls/wall_screen.hpp) must never
// drop a contact that wall_contact() finds, for any kind of wall at any pose,
// and should reject what is clearly out of reach.
#include <gtest/gtest.h>

#include <random>

#include "walls/wall_motion.hpp"
#include "walls/wall_screen.hpp"
#include "wall_test_helpers.hpp"

namespace gs {
namespace {

// A wall turning about a tilted axis and drifting, posed at time t.
Wall moved(Wall w, double t) {
  w.axis_point = {0.3, -0.2, 0.1};
  w.angular_velocity = {0.4, -1.1, 2.3};
  w.velocity = {0.05, 0.02, -0.03};
  update_wall_pose(w, t);
  return w;
}

// Centres scattered within 2 radii of the wall's surface, where contacts and
// near misses both occur; `offset` moves the whole scene away from the origin.
void expect_screen_keeps_every_contact(const Wall& w, const Vec3d& offset) {
  Wall placed = w;
  placed.point += offset;
  placed.axis_point += offset;
  const WallScreen screen = wall_screen(placed);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int contacts = 0, rejected = 0;
  for (int k = 0; k < 20000; ++k) {
    const double radius = 0.01 * (1 + u(rng) * 0.9);
    const Vec3d x = offset + Vec3d(0.3 + 0.2 * u(rng), -0.2 + 0.2 * u(rng), 0.1 + 0.2 * u(rng));
    WallContact c;
    const bool touches = wall_contact(placed, x, radius, c);
    const bool may = wall_may_touch(screen, x, radius);
    if (touches) {
      ++contacts;
      ASSERT_TRUE(may) << "contact dropped: overlap " << c.overlap << " at k = " << k;
    }
    rejected += !may;
  }
  EXPECT_GT(contacts, 0);
  EXPECT_GT(rejected, 1000);  // the screen does reject what is out of reach
}

TEST(WallScreen, KeepsEveryPlaneContact) {
  const Wall plane = make_wall(WallKind::plane, {0.3, -0.2, 0.1}, {1, 2, -0.5});
  for (double t : {0.0, 0.7, 3.1}) {
    expect_screen_keeps_every_contact(moved(plane, t), {0, 0, 0});
    expect_screen_keeps_every_contact(moved(plane, t), {1e3, -1e3, 1e3});
    expect_screen_keeps_every_contact(moved(plane, t), {1e5, 1e5, -1e5});
  }
}

TEST(WallScreen, KeepsEveryDiskContact) {
  const Wall disk = make_wall(WallKind::disk, {0.3, -0.2, 0.1}, {0, 0.3, 1}, 0.1);
  for (double t : {0.0, 1.3}) {
    expect_screen_keeps_every_contact(moved(disk, t), {0, 0, 0});
    expect_screen_keeps_every_contact(moved(disk, t), {1e5, -1e5, 1e5});
  }
}

TEST(WallScreen, KeepsEveryCylinderContact) {
  // Radius 0.15 about an axis through the scatter region: centres fall
  // inside near the axis (rejected), near the surface and outside it.
  const Wall cylinder = make_wall(WallKind::cylinder, {0.3, -0.2, -0.2}, {0.1, 0, 1}, 0.15, 0.6);
  for (double t : {0.0, 0.4, 2.2}) {
    expect_screen_keeps_every_contact(moved(cylinder, t), {0, 0, 0});
    expect_screen_keeps_every_contact(moved(cylinder, t), {-1e3, 1e3, 1e3});
    expect_screen_keeps_every_contact(moved(cylinder, t), {1e5, 1e5, 1e5});
  }
}

TEST(WallScreen, RejectsASphereClearOfAPlane) {
  const WallScreen s = wall_screen(make_wall(WallKind::plane, {0, 0, 0}, {0, 0, 1}));
  EXPECT_FALSE(wall_may_touch(s, {0, 0, 0.0101}, 0.01));
  EXPECT_TRUE(wall_may_touch(s, {0, 0, 0.0099}, 0.01));
  EXPECT_TRUE(wall_may_touch(s, {0, 0, -5}, 0.01));  // behind: wall_contact decides
}

TEST(WallScreen, RejectsASphereNearACylinderAxis) {
  const WallScreen s = wall_screen(make_wall(WallKind::cylinder, {0, 0, 0}, {0, 0, 1}, 0.05, 0.3));
  EXPECT_FALSE(wall_may_touch(s, {0.0399, 0, 0.1}, 0.01));
  EXPECT_TRUE(wall_may_touch(s, {0.0401, 0, 0.1}, 0.01));
  EXPECT_TRUE(wall_may_touch(s, {0.2, 0, 0.1}, 0.01));  // outside: wall_contact decides
}

}  // namespace
}  // namespace gs
