// Stability case 6 (docs/STABILITY.md): light and heavy spheres of equal size
// (density ratio 1:1000) settling together with friction. The time step is
// the loader's largest (contact/stable_step.hpp), set by the light-light
// pair (m* = m_light / 2), 31 times shorter than the heavy-heavy one. A light
// sphere squeezed between heavy ones is a stiff spring on a tiny mass; the
// step must hold it.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kHeavy = 2500, kLight = 2.5, kStiffness = 1000, kRestitution = 0.5;
constexpr double kMu = 0.5, kGravity = 9.81;

struct Bed {
  SceneSpec scene;
  double fill_height;
};

// Half heavy (material 0), half light (material 1), mixed at random in a
// square box to a solid fraction of 0.3.
Bed contrast_bed(std::size_t count, double width) {
  Bed bed{base_scene(kHeavy, kStiffness, kRestitution, kMu), 0};
  SceneSpec& scene = bed.scene;
  scene.effects = kFriction;
  scene.precision = Precision::fp32;
  scene.gravity = {0, 0, -kGravity};
  const int light = add_material(scene, "light", kLight);
  bed.fill_height = double(count) * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3) / 0.3 / (width * width);
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {width + 0.001, width + 0.001, bed.fill_height + 0.001};
  scene.walls = box_walls({0, 0, 0}, {width, width, bed.fill_height});
  add_random_fill(scene, 0, count, kRadius, kRadius, {0, 0, 0}, {width, width, bed.fill_height}, 17);
  std::mt19937 rng(23);
  for (ParticleInit& p : scene.particles)
    if (rng() % 2) p.material = light;
  set_largest_accepted_step(scene);
  return bed;
}

class StabilityDensityContrastTest : public testing::TestWithParam<Backend> {};

// Bounds:
// * the step is the light pair's: the largest the loader accepts;
// * energy: kinetic + potential never above E0 by 1e-3 of it (damped);
// * overlap below v sqrt(M / 2k) / R with v = sqrt(2 g H): a heavy sphere
//   landing from the fill height on a light one lying on the floor drives
//   two springs in series with its own mass (the light one adds nothing),
//   3% of R here; the static load (a few heavy layers, M g / k each) is 0.1%;
// * health checks (finite, none lost, inside the box).
TEST_P(StabilityDensityContrastTest, LightAndHeavySettleAtTheLightStep) {
  const Bed bed = contrast_bed(short_or_long<std::size_t>(300, 40000), short_or_long(0.02, 0.2));
  const SceneSpec& scene = bed.scene;
  const double light_mass = stored_sphere_mass(kRadius, kLight), heavy_mass = stored_sphere_mass(kRadius, kHeavy);
  EXPECT_NEAR(scene.contact_time / linear_contact_time(kStiffness, 0.5 * light_mass, kRestitution), 1.0, 1e-6);
  Simulation sim(scene, {GetParam()});
  const double e0 = mechanical_energy(sim.snapshot(), scene.gravity);
  const long long steps = std::llround(short_or_long(0.015, 0.1) / scene.time_step);
  const int samples = 20;
  const RunRecord r = run_and_watch(sim, samples, steps / samples, e0);
  const double bound = std::sqrt(2 * kGravity * bed.fill_height) * std::sqrt(heavy_mass / (2 * kStiffness)) / kRadius;
  std::printf("[ measured ] %zu spheres, dt %.3g s, %lld steps: energy growth %.3g E0, max overlap %.4f R (bound "
              "%.4f R), max speed %.3g m/s\n",
              scene.particles.size(), scene.time_step, sim.step_count(), r.energy_growth, r.overlap.worst(), bound,
              r.speed);
  EXPECT_EQ(r.failures, 0);
  EXPECT_LT(r.energy_growth, 1e-3);
  EXPECT_LT(r.overlap.worst(), bound);
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityDensityContrastTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
