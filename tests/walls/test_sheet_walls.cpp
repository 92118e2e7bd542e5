// Plates with holes and cones (walls/sheet_geometry.hpp): the contact of a
// sphere is with the nearest point of the sheet, checked against the
// distances worked out by hand (to a plane, to a rim circle, to the sides of
// a rectangle, to a cone's generatrix) and, for a rectangular hole, against
// a brute-force search along its rim; then in the engine on every backend: a
// sphere over the hole falls through untouched, one on the flat rests as on a
// plane, one on a hopper's wall slides down it at g cos(alpha).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "contact/contact_time.hpp"
#include "support/support.hpp"
#include "walls/wall_geometry.hpp"
#include "walls/wall_motion.hpp"

namespace gs::test {
namespace {

constexpr double kTol = 1e-15;

// A plate in the plane z = 0.01 with a circular hole of radius 0.02, out to radius 0.05.
Wall annulus() {
  Wall w;
  w.kind = WallKind::plate;
  w.point = Vec3d(0.001, -0.002, 0.01);
  w.normal = Vec3d(0, 0, 1);
  w.radius = 0.05;
  w.hole_half[0] = 0.02;
  return w;
}

TEST(SheetWalls, SphereOverTheHoleIsUntouched) {
  const Wall w = annulus();
  WallContact c;
  for (double z : {-0.01, 0.0, 0.01, 0.02})  // above, in and below the plate's plane
    EXPECT_FALSE(wall_contact(w, w.point + Vec3d(0.012, 0.003, z - 0.01), 0.005, c)) << "z = " << z;
}

TEST(SheetWalls, SphereOnTheFlatTouchesAsOnAPlaneFromEitherSide) {
  const Wall w = annulus();
  WallContact c;
  ASSERT_TRUE(wall_contact(w, w.point + Vec3d(0.03, 0.01, 0.004), 0.005, c));
  EXPECT_NEAR(c.overlap, 0.001, kTol);
  EXPECT_EQ(c.normal.z, 1.0);
  EXPECT_NEAR(c.point.z, 0.01, kTol);
  ASSERT_TRUE(wall_contact(w, w.point + Vec3d(-0.01, 0.025, -0.003), 0.005, c));
  EXPECT_NEAR(c.overlap, 0.002, kTol);
  EXPECT_EQ(c.normal.z, -1.0);
  EXPECT_FALSE(wall_contact(w, w.point + Vec3d(0.03, 0.01, 0.0051), 0.005, c));
}

// Near the hole's rim the contact is with the rim circle: the distance from
// the centre to the circle, the normal from the nearest rim point.
TEST(SheetWalls, RimContactIsTheDistanceToTheRimCircle) {
  const Wall w = annulus();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), in(0.016, 0.02), height(-0.004, 0.004);
  for (int k = 0; k < 200; ++k) {
    const double phi = angle(rng), rho = in(rng), h = height(rng);
    const Vec3d x = w.point + Vec3d(rho * std::cos(phi), rho * std::sin(phi), h);
    const double distance = std::hypot(0.02 - rho, h);  // to the circle, in the half-plane through the axis
    const Vec3d rim = w.point + Vec3d(0.02 * std::cos(phi), 0.02 * std::sin(phi), 0);
    WallContact c;
    const bool touches = wall_contact(w, x, 0.005, c);
    ASSERT_EQ(touches, distance < 0.005) << "rho = " << rho << ", h = " << h;
    if (!touches) continue;
    EXPECT_NEAR(c.overlap, 0.005 - distance, 1e-15);
    EXPECT_NEAR(norm(c.point - rim), 0, 1e-15);
    EXPECT_NEAR(norm(c.normal - (x - rim) * (1 / distance)), 0, 1e-12);
  }
  // Beyond the outer circle: the distance to it.
  WallContact c;
  ASSERT_TRUE(wall_contact(w, w.point + Vec3d(0, 0.053, 0.004), 0.006, c));
  EXPECT_NEAR(c.overlap, 0.006 - 0.005, 1e-15);
}

// A rectangular hole 0.04 x 0.02, turned by 30 degrees in a tilted plate: the
// nearest rim point by brute force along the four sides.
TEST(SheetWalls, RectangularHoleRimAgreesWithABruteForceSearch) {
  Wall w;
  w.kind = WallKind::plate;
  w.point = Vec3d(0.1, 0.2, -0.3);
  w.normal = Vec3d(0.3, -0.2, 1) * (1 / norm(Vec3d(0.3, -0.2, 1)));
  const Vec3d along = cross(w.normal, Vec3d(0, 1, 0));
  const Vec3d t0 = along * (1 / norm(along)), t1 = cross(w.normal, t0);
  w.tangent = std::cos(0.5236) * t0 + std::sin(0.5236) * t1;
  const Vec3d across = cross(w.normal, w.tangent);
  w.radius = std::numeric_limits<double>::infinity();
  w.hole_half[0] = 0.02;
  w.hole_half[1] = 0.01;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-0.025, 0.025), v(-0.015, 0.015), h(-0.004, 0.004);
  int rim_contacts = 0;
  for (int k = 0; k < 100; ++k) {
    const double a = u(rng), b = v(rng), z = h(rng);
    const Vec3d x = w.point + a * w.tangent + b * across + z * w.normal;
    double nearest = std::hypot(std::max(0.0, 0.0), z);  // on the solid: the plane
    if (std::abs(a) < 0.02 && std::abs(b) < 0.01) {  // over the hole: the nearest of 4 x 20000 rim points
      nearest = 1;
      for (int s = 0; s <= 20000; ++s) {
        const double f = double(s) / 20000;
        const Vec3d rim[4] = {(-0.02 + 0.04 * f) * w.tangent - 0.01 * across, (-0.02 + 0.04 * f) * w.tangent + 0.01 * across,
                              -0.02 * w.tangent + (-0.01 + 0.02 * f) * across, 0.02 * w.tangent + (-0.01 + 0.02 * f) * across};
        for (const Vec3d& r : rim) nearest = std::min(nearest, norm(x - w.point - r));
      }
    } else {
      nearest = std::abs(z);
    }
    WallContact c;
    const bool touches = wall_contact(w, x, 0.005, c);
    if (std::abs(nearest - 0.005) < 1e-6) continue;  // too close to call with the sampled rim
    ASSERT_EQ(touches, nearest < 0.005) << "a = " << a << ", b = " << b << ", z = " << z;
    if (!touches) continue;
    rim_contacts += std::abs(a) < 0.02 && std::abs(b) < 0.01;
    EXPECT_NEAR(c.overlap, 0.005 - nearest, 1e-6);  // the sampled rim's spacing: 2e-6 m
    EXPECT_NEAR(norm(x - c.point), 0.005 - c.overlap, 1e-15);
  }
  EXPECT_GT(rim_contacts, 5);
}

// A hopper: base_radius r0 at the base, half angle alpha. A centre at
// height s, a distance rho from the axis, is (r0 + s tan(alpha) - rho)
// cos(alpha) from the wall; a sphere of radius r on the axis touches it from
// s* = (r / cos(alpha) - r0) / tan(alpha) down.
TEST(SheetWalls, ConeDistanceAndTheHeightASphereRestsAt) {
  const double r0 = 0.002, alpha = 30 * M_PI / 180, L = 0.1, r = 0.004;
  Wall w;
  w.kind = WallKind::cone;
  w.point = Vec3d(0.02, 0.01, -0.05);
  w.normal = Vec3d(0, 0, 1);
  w.radius = r0;
  w.length = L;
  w.end_radius = r0 + L * std::tan(alpha);
  for (double s : {0.01, 0.03, 0.07})
    for (double rho : {0.0, 0.003, 0.006}) {
      const double distance = (r0 + s * std::tan(alpha) - rho) * std::cos(alpha);
      WallContact c;
      const Vec3d x = w.point + Vec3d(rho * std::cos(1.0), rho * std::sin(1.0), s);
      const bool touches = wall_contact(w, x, 0.02, c);
      ASSERT_EQ(touches, distance < 0.02);
      if (!touches) continue;
      EXPECT_NEAR(c.overlap, 0.02 - distance, 1e-15) << "s = " << s << ", rho = " << rho;
      if (rho > 0) {
        EXPECT_NEAR(c.normal.z, std::sin(alpha), 1e-15);  // inwards and up the axis
      }
    }
  const double rest = (r / std::cos(alpha) - r0) / std::tan(alpha);
  WallContact c;
  EXPECT_FALSE(wall_contact(w, w.point + Vec3d(1e-9, 0, rest + 1e-7), r, c));
  ASSERT_TRUE(wall_contact(w, w.point + Vec3d(1e-9, 0, rest - 1e-6), r, c));
  EXPECT_NEAR(c.overlap, 1e-6 * std::sin(alpha) + 1e-9 * std::cos(alpha), 1e-15);  // down by 1e-6, out by 1e-9
  // Below the outlet, the contact is with the outlet's rim circle.
  ASSERT_TRUE(wall_contact(w, w.point + Vec3d(0.004, 0, -0.002), r, c));
  EXPECT_NEAR(c.overlap, r - std::hypot(0.002, 0.002), 1e-15);
}

class SheetWallEngineTest : public testing::TestWithParam<Backend> {};

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;

SceneSpec falling_scene() {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution);
  scene.gravity = {0, 0, -kGravity};
  scene.time_step = linear_contact_time(kStiffness, stored_sphere_mass(kRadius, kDensity), kRestitution) / 50;
  return scene;
}

// A sphere dropped onto the plate's flat follows the run on a plane to
// rounding; one dropped over the hole falls through it untouched.
TEST_P(SheetWallEngineTest, PlateHoldsOnItsFlatAndLetsThroughItsHole) {
  Wall plate = plane_wall({0, 0, 0}, {0, 0, 1});
  plate.kind = WallKind::plate;
  plate.radius = 0.015;
  plate.hole_half[0] = 0.004;
  SceneSpec on_plate = falling_scene(), on_plane = falling_scene();
  on_plate.walls = {plate};
  on_plane.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  on_plate.particles = on_plane.particles = {particle(0, kRadius, {0.008, 0.001, 1.2 * kRadius}),
                                             particle(1, kRadius, {-0.001, 0.0015, 1.2 * kRadius})};
  on_plane.particles.pop_back();  // the plane has no hole
  Simulation a(on_plate, {GetParam()}), b(on_plane, {GetParam()});
  a.run(8000);  // 0.05 s: the bounces and the rest
  b.run(8000);
  const ParticleSnapshot s = a.snapshot(), p = b.snapshot();
  EXPECT_LT(norm(s.position[0] - p.position[0]), 1e-15);
  const double m = stored_sphere_mass(kRadius, kDensity);
  EXPECT_NEAR(s.position[0].z, kRadius - m * kGravity / kStiffness, 1e-3 * m * kGravity / kStiffness);
  // Free fall from rest: z = z0 - g t^2 / 2, exact in velocity Verlet.
  const double t = a.time();
  EXPECT_NEAR(s.position[1].z, 1.2 * kRadius - 0.5 * kGravity * t * t, 1e-14);
  EXPECT_EQ(s.force[1].z, 0.0);
}

// A frictionless sphere on the inside of a hopper wall, with gravity along
// -axis, slides down the generatrix at g cos(alpha), pressed onto it by
// m g sin(alpha).
TEST_P(SheetWallEngineTest, SphereSlidesDownAHopperWallAtGCosAlpha) {
  const double alpha = 35 * M_PI / 180, r0 = 0.002, m = stored_sphere_mass(kRadius, kDensity);
  Wall cone;
  cone.kind = WallKind::cone;
  cone.point = Vec3d(0, 0, -0.018);
  cone.normal = Vec3d(0, 0, 1);
  cone.radius = r0;
  cone.length = 0.03;
  cone.end_radius = r0 + 0.03 * std::tan(alpha);
  SceneSpec scene = falling_scene();
  scene.walls = {cone};
  // On the meridian in the x-z plane, at s = 0.02 along the axis, the centre
  // at the equilibrium distance R - m g sin(alpha) / k inside the wall.
  const double s0 = 0.02, d0 = kRadius - m * kGravity * std::sin(alpha) / kStiffness;
  const Vec3d down(-std::sin(alpha), 0, -std::cos(alpha));  // along the generatrix, towards the outlet
  const Vec3d inward(-std::cos(alpha), 0, std::sin(alpha));
  const Vec3d wall_point = cone.point + Vec3d(r0 + s0 * std::tan(alpha), 0, s0);
  scene.particles = {particle(0, kRadius, wall_point + d0 * inward)};
  Simulation sim(scene, {GetParam()});
  sim.run(2000);
  const ParticleSnapshot p = sim.snapshot();
  const double t = sim.time(), along = dot(p.position[0] - (wall_point + d0 * inward), down);
  EXPECT_NEAR(along, 0.5 * kGravity * std::cos(alpha) * t * t, 1e-3 * 0.5 * kGravity * t * t);
  EXPECT_NEAR(dot(p.force[0], inward), m * kGravity * std::sin(alpha), 1e-3 * m * kGravity);
}

INSTANTIATE_TEST_SUITE_P(Backends, SheetWallEngineTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
