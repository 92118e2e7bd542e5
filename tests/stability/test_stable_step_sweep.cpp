// Stability case 10 (docs/STABILITY.md): every scene the loader accepts is
// stable. Poured beds at the largest step the loader accepts
// (contact/stable_step.hpp) over the parameters it allows: restitution
// 0.05-1, k_t / k_n 0.1-3, friction 0-1, rolling resistance on and off, the
// linear and the Hertz-Mindlin models. A dissipative bed must come to rest
// and stay there; a bed without any dissipation (e = 1) must keep its energy.
// At the old limit, 0.2 t_c, the bed (e = 0.3, friction 0.5, k_t =
// 2/7 k_n) erupted again and again: the limit then ignored the tangential
// springs acting through rotation in a dense bed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.001, kDensity = 2500, kGravity = 9.81;

struct SweepCase {
  ContactModel model;
  double restitution, tangential_ratio, friction;
  bool rolling;
};

std::string describe(const SweepCase& c) {
  char text[160];
  std::snprintf(text, sizeof text, "%s e %.2f k_t/k_n %.2f mu %.1f rolling %s",
                c.model == ContactModel::linear ? "linear" : "hertz", c.restitution, c.tangential_ratio, c.friction,
                c.rolling ? "on" : "off");
  return text;
}

// 250 spheres (radii 0.9-1.1 R) poured from a loose fill into a box 12 R
// wide. The linear spring is soft (k_n = 200 N/m: static overlaps ~1 % of
// R at the bottom) to keep the run short; stability depends on dt / t_c, not
// on k. Hertz: E = 5 MPa, a contact time of the same order.
struct Pour {
  SceneSpec scene;
  double fill_height;
};

Pour pour(const SweepCase& c) {
  Pour p{base_scene(kDensity, 200, c.restitution, c.friction, c.model), 0};
  SceneSpec& s = p.scene;
  s.materials[0].youngs_modulus = 5e6;
  s.materials[0].poisson_ratio = 0.3;
  s.pairs[0].stiffness_tangential = c.tangential_ratio * 200;
  s.pairs[0].stiffness_rolling = c.tangential_ratio * 200;
  s.pairs[0].rolling_friction = c.rolling ? 0.2 : 0;
  s.effects = kFriction | (c.rolling ? kRollingResistance : 0u);
  s.precision = Precision::fp32;
  s.gravity = {0, 0, -kGravity};
  const std::size_t count = 250;
  const double width = 12 * kRadius;
  p.fill_height = double(count) * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3) / 0.3 / (width * width);
  s.domain_min = {-0.001, -0.001, -0.001};
  s.domain_max = {width + 0.001, width + 0.001, p.fill_height + 0.003};
  s.walls = box_walls({0, 0, 0}, {width, width, p.fill_height + 0.002});
  add_random_fill(s, 0, count, 0.9 * kRadius, 1.1 * kRadius, {0, 0, 0}, {width, width, p.fill_height}, 17);
  set_largest_accepted_step(s);
  return p;
}

const SweepCase kCases[] = {
    // the bed, and its neighbours in restitution and tangential stiffness
    {ContactModel::linear, 0.3, 2.0 / 7.0, 0.5, false},
    {ContactModel::linear, 0.05, 2.0 / 7.0, 0.5, false},
    {ContactModel::linear, 0.05, 3.0, 1.0, false},
    {ContactModel::linear, 0.05, 0.1, 0.0, false},
    {ContactModel::linear, 0.3, 1.0, 1.0, true},
    {ContactModel::linear, 0.5, 3.0, 0.5, true},
    {ContactModel::linear, 0.7, 0.1, 1.0, true},
    {ContactModel::linear, 0.7, 1.0, 0.0, false},
    {ContactModel::linear, 0.9, 2.0 / 7.0, 0.2, false},
    {ContactModel::linear, 1.0, 2.0 / 7.0, 0.5, false},
    {ContactModel::linear, 1.0, 3.0, 1.0, true},
    {ContactModel::hertz_mindlin, 0.05, 0, 0.5, false},
    {ContactModel::hertz_mindlin, 0.3, 0, 1.0, true},
    {ContactModel::hertz_mindlin, 0.7, 0, 0.5, false},
    {ContactModel::hertz_mindlin, 1.0, 0, 0.5, true},
};

class StabilityStableStepSweepTest : public testing::TestWithParam<Backend> {};

// Bounds, sampled 40 times over 0.4 s (frictionless beds, which flow and
// slosh longer: 1.2 s; the fill falls in ~0.07 s):
// * health checks (finite, none lost, inside the box) throughout;
// * energy: kinetic + potential never above E0 by 1e-3 of it;
// * e < 1: at rest over the last quarter, the translational kinetic energy
//   below 1e-4 N m g R (measured at most 2.2e-6 at 0.7-1 times the limit on
//   the CPU; at 2.5 times the limit a bed keeps 1.5e-4 and another faults).
//   Rotation is left out of this bound: spin about a contact's normal meets
//   no resistance in either contact law, so a settled bed can keep spinning
//   particles. That spin is bounded (the energy bound above holds) but does
//   not decay, and its size is a matter of rounding: 1.5e-4 N m g R in one
//   CPU bed at 0.7 times the limit, 8.1e-4 in one GPU bed at the limit,
//   while the CPU bed's translational energy stayed at 1.5e-7.
//   docs/STABILITY.md, case 10.
// * e = 1 (no dashpot: the bed rings forever): the energy bound alone.
TEST_P(StabilityStableStepSweepTest, PouredBedsSettleAtTheLargestAcceptedStep) {
  for (const SweepCase& c : kCases) {
    SCOPED_TRACE(describe(c));
    const Pour p = pour(c);
    const SceneSpec& scene = p.scene;
    Simulation sim(scene, {GetParam()});
    const double e0 = mechanical_energy(sim.snapshot(), scene.gravity);
    const int samples = 40;
    const long long steps = std::llround((c.friction > 0 ? 0.4 : 1.2) / scene.time_step);
    double late_speed = 0, late_kinetic = 0, late_translational = 0;
    RunRecord worst;
    for (int k = 0; k < samples; ++k) {
      const RunRecord r = run_and_watch(sim, 1, steps / samples, std::fabs(e0));
      worst.failures += r.failures;
      worst.energy_growth = std::max(worst.energy_growth,
                                     (mechanical_energy(sim.snapshot(), scene.gravity) - e0) / std::fabs(e0));
      if (k >= 3 * samples / 4) {
        late_speed = std::max(late_speed, r.speed);
        const ParticleSnapshot s = sim.snapshot();
        late_kinetic = std::max(late_kinetic, kinetic_energy(s));
        late_translational = std::max(late_translational, translational_kinetic_energy(s));
      }
      if (r.failures) break;
    }
    const double unit = double(scene.particles.size()) * stored_sphere_mass(kRadius, kDensity) * kGravity * kRadius;
    std::printf("[ measured ] %s: dt %.4f t_c (%s), %lld steps, energy growth %.3g E0, late max speed %.3g "
                "sqrt(g R), late kinetic energy %.3g (translational %.3g) N m g R\n",
                describe(c).c_str(), scene.time_step / scene.contact_time, scene.stable_step_binding.c_str(),
                sim.step_count(), worst.energy_growth, late_speed / std::sqrt(kGravity * kRadius), late_kinetic / unit, late_translational / unit);
    EXPECT_EQ(worst.failures, 0);
    EXPECT_LT(worst.energy_growth, 1e-3);
    if (c.restitution < 1) {
      EXPECT_LT(late_translational, 1e-4 * unit);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityStableStepSweepTest, testing::ValuesIn(test_backends()),
                         backend_label);

}  // namespace
}  // namespace gs::test
