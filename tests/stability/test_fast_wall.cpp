// Stability case 7 (docs/STABILITY.md): a plane wall driven into a loose bed
// at the wall speed limit of case 2, V = 0.1 R sqrt(k / m) (a sphere at rest
// hit by the wall overlaps it by 10% of R), from a solid fraction of 0.25 to
// 0.45 (below jamming, so the bed is compacted, not crushed). Each step the
// wall advances 4.5% of R; it must push spheres, never pass through them.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kMu = 0.5;
constexpr double kGravity = 9.81;

class StabilityFastWallTest : public testing::TestWithParam<Backend> {};

// Bounds:
// * no sphere behind the moving wall (or any wall), none lost, all finite;
// * speed: a sphere at rest hit by the wall leaves at (1 + e) V; bouncing
//   between the wall and the bed it can gain at most up to (1 + e) / (1 - e) V
//   = 3 V (the fixed point of u -> e u + (1 + e) V), plus the free fall
//   sqrt(2 g H);
// * overlap: a sphere at that speed meeting one coming the other way at the
//   same speed, 2 x 3 V sqrt(m / 2k) = 0.42 R in the worst case; asserted:
//   below 0.25 R (measured ~0.1 R);
// * energy: the wall feeds it in, so no E0 bound; the kinetic energy at the
//   end below N 1/2 m (3 V)^2 (every sphere at the speed bound; the speed
//   bound checked at every sample covers the rest of the run).
TEST_P(StabilityFastWallTest, DrivenWallCompactsBedWithoutEscapes) {
  const std::size_t count = short_or_long<std::size_t>(1000, 50000);
  const double width = short_or_long(0.02, 0.15);
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, kMu);
  scene.effects = kFriction;
  scene.precision = Precision::fp32;
  scene.gravity = {0, 0, -kGravity};
  const double height = double(count) * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3) / 0.25 / (width * width);
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {width + 0.001, width + 0.001, height + 0.001};
  scene.walls = box_walls({0, 0, 0}, {width, width, height});  // the last one, zmax, is the lid
  const double mass = stored_sphere_mass(kRadius, kDensity);
  const double speed = 0.1 * kRadius * std::sqrt(kStiffness / mass);
  scene.walls.back().velocity = {0, 0, -speed};
  add_random_fill(scene, 0, count, kRadius, kRadius, {0, 0, 0}, {width, width, height}, 29);
  set_largest_accepted_step(scene);

  Simulation sim(scene, {GetParam()});
  const double travel = height * (1 - 0.25 / 0.45);
  const long long steps = std::llround(travel / speed / scene.time_step);
  const int samples = 40;
  const RunRecord r = run_and_watch(sim, samples, steps / samples, 1.0);
  const double speed_bound = (1 + kRestitution) / (1 - kRestitution) * speed + std::sqrt(2 * kGravity * height);
  const double energy_bound = double(count) * 0.5 * mass * speed_bound * speed_bound;
  const double e_kin = kinetic_energy(sim.snapshot());
  std::printf("[ measured ] %zu spheres, wall at %.3g m/s (%.3f R per step), %lld steps, lid moved %.3g m: max "
              "speed %.3g m/s (bound %.3g), max overlap %.4f R, final kinetic %.3g of the bound\n",
              count, speed, speed * scene.time_step / kRadius, sim.step_count(), speed * sim.time(), r.speed,
              speed_bound, r.overlap.worst(), e_kin / energy_bound);
  EXPECT_EQ(r.failures, 0);
  EXPECT_LT(r.speed, speed_bound);
  EXPECT_LT(r.overlap.worst(), 0.25);
  EXPECT_LT(e_kin, energy_bound);
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityFastWallTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
