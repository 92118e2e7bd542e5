// Stability case 3 (docs/STABILITY.md): a single column of N >= 200 spheres
// stacked in a narrow box, at rest for a long time at the largest accepted
// time step. The column is a chain of N springs in series; its stiffest mode
// has omega = 2 sqrt(k / m), omega dt < 2 at the largest accepted step, and its
// slowest ones are barely damped (modal damping ratio ~ zeta pi / 2N), so an
// integrator that feeds in energy, or a force that creeps, shows as drift.
// Each contact carries the weight of the spheres above it: the wall contact
// N m g / k, the contact above sphere i (0 = bottom) (N - 1 - i) m g / k.
// The spheres start at that static equilibrium.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

// R = 2^-10 m is exact in fp32.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1e4, kRestitution = 0.5, kGravity = 9.81;

double weight() { return stored_sphere_mass(kRadius, kDensity) * kGravity; }

SceneSpec column_scene(int count, Precision precision) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
  scene.effects = kFriction;
  scene.precision = precision;
  scene.gravity = {0, 0, -kGravity};
  const double half_width = 1.25 * kRadius, height = 2 * kRadius * (count + 1);
  scene.domain_min = {-half_width - 0.001, -half_width - 0.001, -0.001};
  scene.domain_max = {half_width + 0.001, half_width + 0.001, height};
  scene.walls = box_walls({-half_width, -half_width, 0}, {half_width, half_width, height});
  scene.walls.pop_back();  // open at the top
  double z = kRadius - count * weight() / kStiffness;
  for (int i = 0; i < count; ++i) {
    scene.particles.push_back(particle(i, kRadius, {0, 0, z}));
    z += 2 * kRadius - (count - 1 - i) * weight() / kStiffness;
  }
  set_largest_accepted_step(scene);
  return scene;
}

class StabilityDeepColumnTest : public testing::TestWithParam<Backend> {};

// Bounds, over the whole run (sampled 50 times):
// * every overlap matches its static load / k within 1e-8 of the bottom
//   overlap delta_b = 2e-6 m in fp64 (positions ~0.4 m carry 6e-17 m, 3e-11
//   delta_b, per rounding; measured 5e-11) and 1e-5 in fp32 (overlaps and
//   forces rounded to fp32, 6e-8 of each, summed over the chain; measured
//   1.4e-7);
// * no sphere moves by more than that from its start (measured 7e-10 and
//   4e-7), none sideways at all (nothing pushes sideways), speeds below 1e-5
//   of delta_b omega0 (measured 1.4e-7);
// * the usual health checks (finite, none lost, inside).
TEST_P(StabilityDeepColumnTest, StaysAtStaticLoad) {
  const int count = short_or_long(200, 1000);
  const long long steps = short_or_long(20000LL, 200000LL);
  for (const auto& [precision, tolerance] : {std::pair{Precision::fp64, 1e-8}, std::pair{Precision::fp32, 1e-5}}) {
    SCOPED_TRACE(precision_name(precision));
    const SceneSpec scene = column_scene(count, precision);
    const double bottom = count * weight() / kStiffness;  // wall overlap
    const double omega0 = std::sqrt(kStiffness / stored_sphere_mass(kRadius, kDensity));
    Simulation sim(scene, {GetParam()});
    double load_error = 0, drift = 0, sideways = 0, speed = 0;
    const int samples = 50;
    for (int k = 0; k < samples; ++k) {
      sim.run(steps / samples);
      const ParticleSnapshot s = sim.snapshot();
      ASSERT_EQ(expect_healthy(s, scene, sim.walls()), 0);
      load_error = std::max(load_error, std::fabs(kRadius - s.position[0].z - bottom));
      for (int i = 0; i < count; ++i) {
        if (i + 1 < count) {
          const double overlap = 2 * kRadius - norm(s.position[i + 1] - s.position[i]);
          load_error = std::max(load_error, std::fabs(overlap - (count - 1 - i) * weight() / kStiffness));
        }
        drift = std::max(drift, norm(s.position[i] - scene.particles[i].position));
        sideways = std::max({sideways, std::fabs(s.position[i].x), std::fabs(s.position[i].y)});
        speed = std::max(speed, norm(s.velocity[i]));
      }
    }
    std::printf("[ measured ] %d spheres (%d diameters), %lld steps at %.2f t_c: bottom overlap %.4f R; load error "
                "%.3g, drift %.3g (of the bottom overlap), sideways %.3g m, speed %.3g delta omega0\n",
                count, count, sim.step_count(), scene.time_step / scene.contact_time, bottom / kRadius,
                load_error / bottom, drift / bottom, sideways, speed / (bottom * omega0));
    EXPECT_LT(load_error, tolerance * bottom);
    EXPECT_LT(drift, tolerance * bottom);
    EXPECT_EQ(sideways, 0.0);
    EXPECT_LT(speed, 1e-5 * bottom * omega0);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityDeepColumnTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
