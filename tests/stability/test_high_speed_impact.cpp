// Stability case 2 (docs/STABILITY.md): head-on impacts at the speed limit of
// the linear spring. The undamped peak overlap of an impact at relative speed
// v is v sqrt(m* / k); the suite's speed limit is the one that makes it 10%
// of the radius, v_max = 0.1 R sqrt(k / m*) (m* = m / 2 for two spheres,
// m for a sphere on a wall): 14.0 m/s and 9.9 m/s here. Beyond it the
// small-overlap picture of a soft-sphere contact stops being physical.
// Two spheres and a sphere onto a plane wall, at the largest step the loader
// accepts and at t_c / 50; the long variant runs thousands of each at once.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "contact/restitution.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1e5, kRestitution = 0.8;
constexpr double kOverlapLimit = 0.1;  // peak overlap at v_max, relative to R

double mass() { return stored_sphere_mass(kRadius, kDensity); }

// Peak overlap of a damped linear contact hit at relative speed v:
// delta(t) = v / omega_d exp(-zeta omega0 t) sin(omega_d t), largest where
// tan(omega_d t) = sqrt(1 - zeta^2) / zeta.
double damped_peak_overlap(double v, double m_eff) {
  const double zeta = damping_ratio(ContactModel::linear, kRestitution);
  const double omega0 = std::sqrt(kStiffness / m_eff), omega_d = omega0 * std::sqrt(1 - zeta * zeta);
  const double t = std::atan2(std::sqrt(1 - zeta * zeta), zeta) / omega_d;
  return v / omega_d * std::exp(-zeta * omega0 * t) * std::sin(omega_d * t);
}

// `count` sphere pairs approaching along x at relative speed v_pair (ids 2k,
// 2k + 1), on a grid of lanes 4 R apart in (y, z), above `count` spheres
// flying at v_wall onto the plane z = 0 (ids 2 count + k) on a grid in (x, y).
SceneSpec impacts(int count, double v_pair, double v_wall) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution);
  const int side = int(std::ceil(std::sqrt(double(count))));
  const double lane = 4 * kRadius, gap = 0.02 * kRadius;
  scene.domain_min = {-4 * kRadius, -kRadius, -kRadius};
  scene.domain_max = {side * lane + 4 * kRadius, side * lane + kRadius, (side + 2) * lane + 4 * kRadius};
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  for (int k = 0; k < count; ++k) {
    const double y = (k % side + 0.5) * lane, z = (k / side + 2) * lane;
    scene.particles.push_back(particle(2 * k, kRadius, {-kRadius - gap, y, z}, {0.5 * v_pair, 0, 0}));
    scene.particles.push_back(particle(2 * k + 1, kRadius, {kRadius + gap, y, z}, {-0.5 * v_pair, 0, 0}));
  }
  for (int k = 0; k < count; ++k) {
    const double x = (k / side + 0.5) * lane, y = (k % side + 0.5) * lane;
    scene.particles.push_back(particle(2 * count + k, kRadius, {x, y, kRadius + gap}, {0, 0, -v_wall}));
  }
  return scene;
}

class StabilityHighSpeedImpactTest : public testing::TestWithParam<Backend> {};

// Bounds, for every pair and every wall impact:
// * peak overlap (sampled every step) within 2% of the damped analytic peak
//   at t_c / 50 and 10% at the largest accepted step (sampled every step,
//   the discrete peak misses the true one by up to (omega dt)^2 / 8), and never above
//   the undamped 0.1 R;
// * rebound speed / impact speed within 1% of e at t_c / 50 and 5% at the
//   largest accepted step (the discrete contact starts and ends between steps, at any phase);
// * energy: kinetic never above its initial value by more than 1e-9 of it
//   (the elastic energy, left out, is positive; the dashpot removes energy);
// * nothing lost, non-finite, outside the domain or behind the wall.
TEST_P(StabilityHighSpeedImpactTest, ReboundMatchesRestitutionAtTheSpeedLimit) {
  const int count = short_or_long(1, 4096);
  const double v_pair = kOverlapLimit * kRadius / std::sqrt(0.5 * mass() / kStiffness);
  const double v_wall = kOverlapLimit * kRadius / std::sqrt(mass() / kStiffness);
  const double t_c = linear_contact_time(kStiffness, 0.5 * mass(), kRestitution);
  SceneSpec largest = impacts(count, v_pair, v_wall);
  set_largest_accepted_step(largest);
  for (const auto& [fraction, peak_tolerance, restitution_tolerance] :
       {std::tuple{0.02, 0.02, 0.01}, std::tuple{largest.time_step / t_c, 0.1, 0.05}}) {
    SCOPED_TRACE("dt = " + std::to_string(fraction) + " t_c");
    SceneSpec scene = impacts(count, v_pair, v_wall);
    scene.time_step = fraction * t_c;
    Simulation sim(scene, {GetParam()});
    const double e0 = kinetic_energy(sim.snapshot());
    // Both contacts last t_c (pair) and sqrt(2) t_c (wall); run 3 t_c.
    const long long steps = std::llround(3 / fraction);
    std::vector<double> peak(2 * count, 0.0);  // per pair, then per wall sphere
    double growth = -1;
    for (long long n = 0; n < steps; ++n) {
      sim.run(1);
      const ParticleSnapshot s = sim.snapshot();
      growth = std::max(growth, kinetic_energy(s) / e0 - 1);
      for (int k = 0; k < count; ++k) {
        const double d = 2 * kRadius - norm(s.position[2 * k + 1] - s.position[2 * k]);
        peak[k] = std::max(peak[k], d / kRadius);
        peak[count + k] = std::max(peak[count + k], (kRadius - s.position[2 * count + k].z) / kRadius);
      }
    }
    const ParticleSnapshot s = sim.snapshot();
    ASSERT_EQ(expect_healthy(s, scene, sim.walls()), 0);
    const double pair_peak = damped_peak_overlap(v_pair, 0.5 * mass()) / kRadius;
    const double wall_peak = damped_peak_overlap(v_wall, mass()) / kRadius;
    double worst_peak = 0, worst_rebound = 0, largest = 0;
    for (int k = 0; k < count; ++k) {
      const double rebound_pair = (s.velocity[2 * k + 1].x - s.velocity[2 * k].x) / v_pair;
      const double rebound_wall = s.velocity[2 * count + k].z / v_wall;
      worst_rebound = std::max({worst_rebound, std::fabs(rebound_pair / kRestitution - 1),
                                std::fabs(rebound_wall / kRestitution - 1)});
      worst_peak =
          std::max({worst_peak, std::fabs(peak[k] / pair_peak - 1), std::fabs(peak[count + k] / wall_peak - 1)});
      largest = std::max({largest, peak[k], peak[count + k]});
    }
    std::printf("[ measured ] dt %.2f t_c, v_pair %.2f m/s, v_wall %.2f m/s: peak overlap %.4f R (analytic pair "
                "%.4f R, wall %.4f R), worst peak error %.3g, worst restitution error %.3g, energy growth %.3g\n",
                fraction, v_pair, v_wall, largest, pair_peak, wall_peak, worst_peak, worst_rebound, growth);
    EXPECT_LT(worst_peak, peak_tolerance);
    EXPECT_LT(largest, kOverlapLimit);
    EXPECT_LT(worst_rebound, restitution_tolerance);
    EXPECT_LT(growth, 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityHighSpeedImpactTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
