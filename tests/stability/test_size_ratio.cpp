// Stability case 4 (docs/STABILITY.md): a few large spheres settling in a bed
// of small ones, diameter ratios 1:5 and 1:10 (mass ratios 125 and 1000).
// The time step comes from the small-small contact; a large sphere resting on
// small ones loads each contact with a share of its weight, and a small
// sphere squeezed between a large one and the floor sees the large one's
// inertia. Frictionless: at 1:10 a large sphere touches more small ones than
// the 32 contact-history slots allow (docs/STABILITY.md).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kSmall = 0.0005, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;

struct Bed {
  SceneSpec scene;
  double fill_height;
};

// A box `width` x `width` (in large diameters), `large` large spheres (the
// first ids) resting on the floor and small ones filled at random over
// `height` large diameters to a solid fraction `fraction` of all spheres.
struct BedShape {
  double width, height;
  std::size_t large;
  double fraction;
};

Bed mixed_bed(int ratio, const BedShape& shape) {
  Bed bed{base_scene(kDensity, kStiffness, kRestitution), 0};
  SceneSpec& scene = bed.scene;
  scene.precision = Precision::fp32;
  scene.gravity = {0, 0, -kGravity};
  const double large = ratio * kSmall, width = shape.width * 2 * large;
  bed.fill_height = shape.height * 2 * large;
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {width + 0.001, width + 0.001, bed.fill_height + 0.001};
  scene.walls = box_walls({0, 0, 0}, {width, width, bed.fill_height});
  const double sphere = 4.0 / 3.0 * M_PI;
  const double small_volume =
      shape.fraction * width * width * bed.fill_height - shape.large * sphere * std::pow(large, 3);
  const std::size_t small_count = std::size_t(small_volume / (sphere * std::pow(kSmall, 3)));
  const Vec3d lo(0, 0, 0), hi(width, width, bed.fill_height);
  // The large spheres start on the floor; a large sphere landing on a small
  // one crushes it like a stiff spring of its own inertia (see below).
  add_random_fill(scene, 0, shape.large, large, large, lo, {width, width, 2.0001 * large}, 3);
  add_random_fill(scene, 0, small_count, kSmall, kSmall, lo, hi, 5);
  set_largest_accepted_step(scene);
  return bed;
}

// Bounds:
// * energy: kinetic + potential (from the floor) never above its initial
//   value by more than 1e-3 of it (damped, the elastic energy left out);
// * overlap below 5% of the smaller radius (twice the fall below; measured
//   below 1%). The static share of a large sphere's weight on one of ~10 small
//   contacts is M g / (10 k) = 0.25% of r at 1:10; a small sphere falling the
//   fill height onto the floor overlaps v sqrt(m / k) = 2.5% of r
//   (v = sqrt(2 g H)). A small sphere caught between a large one landing at
//   v and the floor sees the large one's inertia, v sqrt(M / 2k) = r per
//   m/s of landing speed at 1:10 (measured: 10% of r when the large sphere
//   started 2 mm above the small ones): physics of the linear spring, not a
//   numerical limit, so the large spheres start on the floor;
// * health checks (finite, none lost, inside the box).
void settle(Backend backend, int ratio, const BedShape& shape, double duration) {
  const Bed bed = mixed_bed(ratio, shape);
  const SceneSpec& scene = bed.scene;
  Simulation sim(scene, {backend});
  const double e0 = mechanical_energy(sim.snapshot(), scene.gravity);
  const long long steps = std::llround(duration / scene.time_step);
  const int samples = 20;
  const RunRecord r = run_and_watch(sim, samples, steps / samples, e0);
  std::printf("[ measured ] 1:%d, %zu spheres, %lld steps of %.3g s: energy growth %.3g E0, max overlap %.4f "
              "(pairs) %.4f (walls) of the smaller radius, max speed %.3g m/s\n",
              ratio, scene.particles.size(), sim.step_count(), scene.time_step, r.energy_growth, r.overlap.particle,
              r.overlap.wall, r.speed);
  EXPECT_EQ(r.failures, 0);
  EXPECT_LT(r.energy_growth, 1e-3);
  EXPECT_LT(r.overlap.worst(), 0.05);
}

// Short: 2 large spheres in ~700 (1:5), 1 in ~1000 (1:10); a small sphere's
// contact search at 1:10 visits ~(20 r)^3 cells worth of small spheres, so
// the short 1:10 bed is kept narrow. Long: 50 large spheres in a box 10
// large diameters wide.
const BedShape kLongShape{10, 1.25, 50, 0.35};

class StabilitySizeRatioTest : public testing::TestWithParam<Backend> {};

TEST_P(StabilitySizeRatioTest, OneToFiveSettles) {
  settle(GetParam(), 5, short_or_long(BedShape{3, 1.25, 2, 0.35}, kLongShape), short_or_long(0.03, 0.2));
}
TEST_P(StabilitySizeRatioTest, OneToTenSettles) {
  settle(GetParam(), 10, short_or_long(BedShape{1.5, 1.5, 1, 0.3}, kLongShape), short_or_long(0.025, 0.2));
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilitySizeRatioTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
