// Two-particle normal impact: contact duration and restitution against the
// analytic solution of the clamped linear spring-dashpot and against an
// independent RK4 integration of the clamped Hertz equation of motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "contact/contact_time.hpp"
#include "contact/restitution.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

struct ImpactResult {
  double contact_time;
  double restitution;
};

constexpr double kRadius = 1e-3, kDensity = 2500, kSpeed = 0.5;  // each sphere approaches at kSpeed

double sphere_mass() { return 4.0 / 3.0 * M_PI * std::pow(kRadius, 3) * kDensity; }

// Runs two spheres head on and times the contact from the gap.
ImpactResult simulate_impact(SceneSpec scene, Backend backend, double dt) {
  scene.particles = {particle(0, kRadius, {-kRadius * 1.01, 0, 0}, {kSpeed, 0, 0}),
                     particle(1, kRadius, {kRadius * 1.01, 0, 0}, {-kSpeed, 0, 0})};
  scene.time_step = dt;
  Simulation sim(scene, {backend});
  double start = -1, end = -1;
  for (int step = 0; step < 2000000 && end < 0; ++step) {
    sim.run(1);
    const ParticleSnapshot s = sim.snapshot();
    const bool touching = norm(s.position[1] - s.position[0]) < 2 * kRadius;
    if (touching && start < 0) start = sim.time();
    if (!touching && start >= 0) end = sim.time();
  }
  const ParticleSnapshot s = sim.snapshot();
  return {end - start, (s.velocity[1].x - s.velocity[0].x) / (2 * kSpeed)};
}

// Independent reference: m* x'' = -F(x, x') for the overlap x, RK4.
ImpactResult integrate_reference(const std::function<double(double, double)>& force, double m_eff, double v0) {
  double x = 0, v = v0, t = 0;
  const double h = 1e-10;
  auto acc = [&](double xx, double vv) { return -force(xx, vv) / m_eff; };
  do {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    t += h;
  } while (x > 0);
  return {t, -v / v0};
}

class ImpactTest : public testing::TestWithParam<Backend> {};

// The clamped force k x + c x' returns to zero at omega_d t = pi - 2 arcsin zeta,
// with the spheres still overlapping by 2 zeta e v0 / omega_0 (Schwager &
// Poeschel 2007); they then coast apart at e v0, so the spheres touch for
// (pi - 2 arcsin zeta) / omega_d + 2 zeta / omega_0.
double clamped_linear_touch_time(double k, double m_eff, double e) {
  const double zeta = damping_ratio(ContactModel::linear, e), omega0 = std::sqrt(k / m_eff);
  return (M_PI - 2 * std::asin(zeta)) / (omega0 * std::sqrt(1 - zeta * zeta)) + 2 * zeta / omega0;
}

TEST_P(ImpactTest, LinearContactTimeAndRestitution) {
  const double k = 1e5, e = 0.78;
  const SceneSpec scene = base_scene(kDensity, k, e);
  const double m_eff = sphere_mass() / 2;
  const double t_c = clamped_linear_touch_time(k, m_eff, e);
  const ImpactResult r = simulate_impact(scene, GetParam(), t_c / 500);
  EXPECT_NEAR(r.contact_time / t_c, 1.0, 0.01);
  EXPECT_NEAR(r.restitution / e, 1.0, 0.01);
}

TEST_P(ImpactTest, HertzUndampedMatchesAnalyticDuration) {
  SceneSpec scene = base_scene(kDensity, 0, 1.0, 0, ContactModel::hertz_mindlin);
  scene.materials[0].youngs_modulus = 5e6;
  scene.materials[0].poisson_ratio = 0.25;
  const double nu = 0.25, youngs_eff = 5e6 / (2 * (1 - nu * nu)), r_eff = kRadius / 2, m_eff = sphere_mass() / 2;
  const double v = 2 * kSpeed;
  // Hertz: t_c = 2.9432 delta_max / v with delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5).
  const double delta_max = std::pow(15 * m_eff * v * v / (16 * youngs_eff * std::sqrt(r_eff)), 0.4);
  const double t_c = 2.94324 * delta_max / v;
  const ImpactResult r = simulate_impact(scene, GetParam(), t_c / 500);
  EXPECT_NEAR(r.contact_time / t_c, 1.0, 0.01);
  EXPECT_NEAR(r.restitution, 1.0, 0.01);
}

TEST_P(ImpactTest, HertzDampedMatchesReferenceIntegration) {
  const double e = 0.6, nu = 0.25;
  SceneSpec scene = base_scene(kDensity, 0, e, 0, ContactModel::hertz_mindlin);
  scene.materials[0].youngs_modulus = 5e6;
  scene.materials[0].poisson_ratio = nu;
  const double youngs_eff = 5e6 / (2 * (1 - nu * nu)), r_eff = kRadius / 2, m_eff = sphere_mass() / 2;
  const double zeta = damping_ratio(ContactModel::hertz_mindlin, e);
  auto force = [&](double x, double rate) {
    const double a = std::sqrt(r_eff * std::max(x, 0.0));  // RK stages may step past x = 0
    const double f =
        4.0 / 3.0 * youngs_eff * a * x + 2 * std::sqrt(5.0 / 6.0) * zeta * std::sqrt(2 * youngs_eff * a * m_eff) * rate;
    return std::max(f, 0.0);  // no pull
  };
  const ImpactResult ref = integrate_reference(force, m_eff, 2 * kSpeed);
  EXPECT_NEAR(ref.restitution / e, 1.0, 1e-4);  // the damping ratio is that of the clamped law
  const ImpactResult r = simulate_impact(scene, GetParam(), ref.contact_time / 500);
  EXPECT_NEAR(r.contact_time / ref.contact_time, 1.0, 0.01);
  EXPECT_NEAR(r.restitution / ref.restitution, 1.0, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Backends, ImpactTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
