// Stability case 1 (docs/STABILITY.md): a dense bed settling with friction at
// the largest time step the loader accepts (contact/stable_step.hpp). In a
// dense bed a sphere pressed by many neighbours sees a stiffer spring than
// the lone contact t_c is computed for; the limit's dense-bed modes must
// cover it.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kMu = 0.5;
constexpr double kGravity = 9.81;

struct Bed {
  SceneSpec scene;
  double fill_height;  // top of the fill region: the highest fall
};

// `count` spheres (radii 0.9-1.1 R) poured at random into a square box of
// `width`, filled to a solid fraction of 0.3, falling under gravity.
Bed settling_bed(std::size_t count, double width) {
  Bed bed{base_scene(kDensity, kStiffness, kRestitution, kMu), 0};
  SceneSpec& scene = bed.scene;
  scene.effects = kFriction;
  scene.precision = Precision::fp32;
  scene.gravity = {0, 0, -kGravity};
  const double volume = double(count) * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  bed.fill_height = volume / 0.3 / (width * width);
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {width + 0.001, width + 0.001, bed.fill_height + 0.003};
  scene.walls = box_walls({0, 0, 0}, {width, width, bed.fill_height + 0.002});
  add_random_fill(scene, 0, count, 0.9 * kRadius, 1.1 * kRadius, {0, 0, 0}, {width, width, bed.fill_height}, 11);
  set_largest_accepted_step(scene);
  return bed;
}

class StabilityStiffContactsTest : public testing::TestWithParam<Backend> {};

// Bounds:
// * energy: kinetic + potential never exceeds its initial value by more than
//   1e-3 of it. The dashpot and friction only remove energy, and the elastic
//   energy left out is positive; Verlet's shadow-energy error at omega dt =
//   0.63 is (omega dt)^2 / 8 = 5% of the energy held in springs, itself a few
//   percent of E0 at most.
// * overlap: below the head-on overlap of a sphere falling the whole fill
//   height onto the floor, v sqrt(m / k) with v = sqrt(2 g H) (the heaviest
//   sphere against a wall: the largest m*), ~8% of R here.
// * at rest at the end: the static overlap of the bed under its weight, the
//   column load of ~n layers m g / k, well below 1% of R; the kinetic energy
//   below 1e-4 of E0 (measured ~1e-5: friction lets the bed creep a while;
//   an unstable step would keep it ringing instead).
TEST_P(StabilityStiffContactsTest, DenseBedSettlesAtTheStableStepLimit) {
  const std::size_t count = short_or_long<std::size_t>(800, 40000);
  const double width = short_or_long(0.02, 0.2);
  const Bed bed = settling_bed(count, width);
  const SceneSpec& scene = bed.scene;
  Simulation sim(scene, {GetParam()});
  const double e0 = mechanical_energy(sim.snapshot(), scene.gravity);
  const long long steps = std::llround(short_or_long(0.2, 0.5) / scene.time_step);
  const int samples = 40;
  const RunRecord r = run_and_watch(sim, samples, steps / samples, e0);
  ASSERT_EQ(r.failures, 0);

  const double heavy = stored_sphere_mass(1.1 * kRadius, kDensity);
  const double impact_overlap = std::sqrt(2 * kGravity * bed.fill_height) * std::sqrt(heavy / kStiffness);
  const ParticleSnapshot s = sim.snapshot();
  const Overlaps at_rest = max_overlaps(s, sim.walls());
  std::printf("[ measured ] dt %.3g s (%.2f t_c), %lld steps; energy growth %.3g E0; max overlap %.4f R "
              "(bound %.4f R); at rest: overlap %.5f R, kinetic %.3g E0\n",
              scene.time_step, scene.time_step / scene.contact_time, sim.step_count(), r.energy_growth,
              r.overlap.worst(), impact_overlap / (0.9 * kRadius), at_rest.worst(), kinetic_energy(s) / e0);
  EXPECT_LT(r.energy_growth, 1e-3);
  EXPECT_LT(r.overlap.worst(), impact_overlap / (0.9 * kRadius));
  EXPECT_LT(at_rest.worst(), 0.01);
  EXPECT_LT(kinetic_energy(s), 1e-4 * e0);
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityStiffContactsTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
