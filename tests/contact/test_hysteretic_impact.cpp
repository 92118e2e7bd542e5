// The hysteretic linear spring (Walton & Braun 1986): a head-on impact
// against the model's closed-form solution. Loading on k_1 to the peak
// overlap delta_max = v0 sqrt(m*/k_1) (a quarter period), unloading on
// k_2 = k_1 / e^2 to the permanent overlap delta_0 = delta_max (1 - e^2) (a
// quarter period of k_2), where the force vanishes and the spheres part at
// e v0 whatever v0; they still overlap, and coast apart for delta_0 / (e v0).
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_time_step.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 1e-3, kDensity = 2500, kLoading = 1e5;  // k_1 [N/m]

struct Impact {
  double touch_time;   // geometric overlap > 0
  double restitution;  // separation speed / approach speed
  double peak_overlap; // the history's delta_max, read while the spheres still overlap
};

Impact collide(double e, double approach_speed, Backend backend, double dt) {
  SceneSpec scene = base_scene(kDensity, kLoading, e, 0, ContactModel::hysteretic_linear);
  const double v = approach_speed / 2;
  scene.particles = {particle(0, kRadius, {-kRadius * 1.001, 0, 0}, {v, 0, 0}),
                     particle(1, kRadius, {kRadius * 1.001, 0, 0}, {-v, 0, 0})};
  scene.time_step = dt;
  Simulation sim(scene, {backend});
  Impact r{-1, 0, 0};
  double start = -1;
  for (int step = 0; step < 1000000 && r.touch_time < 0; ++step) {
    sim.run(1);
    const ParticleSnapshot s = sim.snapshot();
    const bool touching = norm(s.position[1] - s.position[0]) < 2 * kRadius;
    if (touching && start < 0) start = sim.time();
    if (touching) {
      const HostHistory h = sim.history();
      for (std::size_t k = 0; k < std::size_t(h.slots); ++k)
        if (h.partner[k] == 1) r.peak_overlap = h.peak_overlap[k];  // particle 0's contact with 1
    }
    if (!touching && start >= 0) r.touch_time = sim.time() - start;
  }
  const ParticleSnapshot s = sim.snapshot();
  r.restitution = (s.velocity[1].x - s.velocity[0].x) / approach_speed;
  return r;
}

class HystereticImpact : public testing::TestWithParam<Backend> {};

TEST_P(HystereticImpact, RestitutionIsTheRootOfTheStiffnessRatioAtEverySpeed) {
  const double m_eff = stored_sphere_mass(kRadius, kDensity) / 2;
  for (const double e : {0.3, 0.6, 0.9})
    for (const double v0 : {0.2, 2.0}) {
      const double k2 = kLoading / (e * e);
      const double quarter_1 = M_PI / 2 * std::sqrt(m_eff / kLoading), quarter_2 = M_PI / 2 * std::sqrt(m_eff / k2);
      const double peak = v0 * std::sqrt(m_eff / kLoading), permanent = peak * (1 - e * e);
      const double touch = quarter_1 + quarter_2 + permanent / (e * v0);
      const Impact r = collide(e, v0, GetParam(), quarter_2 / 200);
      std::printf("[ measured ] e %.1f, v0 %.1f m/s: restitution %.6f, touch time %.6g s (analytic %.6g), "
                  "peak overlap %.6g m (analytic %.6g)\n",
                  e, v0, r.restitution, r.touch_time, touch, r.peak_overlap, peak);
      EXPECT_NEAR(r.restitution / e, 1.0, 0.005) << "e " << e << ", v0 " << v0;
      EXPECT_NEAR(r.touch_time / touch, 1.0, 0.01) << "e " << e << ", v0 " << v0;
      EXPECT_NEAR(r.peak_overlap / peak, 1.0, 0.005) << "e " << e << ", v0 " << v0;
    }
}

// The unit of fraction_of_contact_time: the two quarter periods, for the
// smallest spheres of the pair.
TEST(HystereticContactTime, IsTheLoadingAndUnloadingQuarterPeriods) {
  SceneSpec scene = base_scene(kDensity, kLoading, 0.5, 0, ContactModel::hysteretic_linear);
  scene.particles = {particle(0, kRadius, {0, 0, 0}), particle(1, 2 * kRadius, {0.01, 0, 0})};
  const double m_eff = sphere_mass(kRadius, kDensity) / 2;
  const double expected = M_PI / 2 * (std::sqrt(m_eff / kLoading) + std::sqrt(m_eff * 0.25 / kLoading));
  EXPECT_NEAR(critical_contact_time(scene) / expected, 1.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Backends, HystereticImpact, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
