// damping_ratio(model, e) against direct integration of the clamped normal
// impacts it claims to calibrate, in units of the impact (m = 1, v0 = 1):
//   linear: x'' = -max(0, x + 2 zeta x'),
//   Hertz, Tsuji dashpot: y'' = -max(0, y^1.5 + sqrt(5) zeta y^0.25 y'),
// each from (0, 1) until the force returns to zero; the rebound speed is then
// the restitution. RK4 with fine steps near the start (y^0.25 is not smooth
// at 0), the end located by bisecting the last step.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "contact/restitution.hpp"

namespace gs::test {
namespace {

struct State {
  double x, v;
};

// Rebound speed for the repulsion `force(x, v)` (unclamped form).
double integrate(const std::function<double(double, double)>& force) {
  auto step = [&](const State& s, double h) {
    auto a = [&](double x, double v) { return -force(x > 0 ? x : 0, v); };
    const double k1x = s.v, k1v = a(s.x, s.v);
    const double k2x = s.v + 0.5 * h * k1v, k2v = a(s.x + 0.5 * h * k1x, k2x);
    const double k3x = s.v + 0.5 * h * k2v, k3v = a(s.x + 0.5 * h * k2x, k3x);
    const double k4x = s.v + h * k3v, k4v = a(s.x + h * k3x, k4x);
    return State{s.x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x), s.v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)};
  };
  auto ended = [&](const State& s) { return s.v < 0 && (s.x <= 0 || force(s.x, s.v) <= 0); };
  State s{0, 1};
  double t = 0;
  while (true) {
    const double h = t < 1e-3 ? 1e-8 : 1e-5;
    const State next = step(s, h);
    if (ended(next)) {
      double lo = 0, hi = h;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ended(step(s, mid)) ? hi : lo) = mid;
      }
      return -step(s, hi).v;
    }
    s = next;
    t += h;
  }
}

TEST(Restitution, DampingRatioGivesTheRestitutionOfTheClampedContact) {
  for (const double e : {0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
    SCOPED_TRACE("e " + std::to_string(e));
    const double zl = damping_ratio(ContactModel::linear, e), zh = damping_ratio(ContactModel::hertz_mindlin, e);
    const double linear = integrate([zl](double x, double v) { return x + 2 * zl * v; });
    const double hertz =
        integrate([zh](double y, double v) { return std::pow(y, 1.5) + std::sqrt(5.0) * zh * std::pow(y, 0.25) * v; });
    EXPECT_NEAR(linear / e, 1.0, 1e-6);
    EXPECT_NEAR(hertz / e, 1.0, 1e-5);
    EXPECT_NEAR(clamped_restitution(zl) / e, 1.0, 1e-12);
  }
}

// The unclamped relation e = exp(-pi zeta / sqrt(1 - zeta^2)) gives too small a
// damping ratio for the clamped contact: the clamp lets the sphere leave before
// the dashpot has taken its share, so that zeta rebounds faster than e.
TEST(Restitution, ClampedContactNeedsMoreDampingThanTheUnclampedRelation) {
  for (const double e : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    const double log_e = std::log(e), unclamped = -log_e / std::sqrt(M_PI * M_PI + log_e * log_e);
    EXPECT_GT(damping_ratio(ContactModel::linear, e), unclamped) << e;
    EXPECT_GT(clamped_restitution(unclamped), e) << e;
  }
}

TEST(Restitution, LimitsAndRange) {
  EXPECT_EQ(damping_ratio(ContactModel::linear, 1.0), 0.0);
  EXPECT_EQ(damping_ratio(ContactModel::hertz_mindlin, 1.0), 0.0);
  EXPECT_NEAR(damping_ratio(ContactModel::linear, std::exp(-2.0)), 1.0, 1e-12);  // critical damping
  EXPECT_GT(damping_ratio(ContactModel::linear, 0.01), 1.0);                     // overdamped below exp(-2)
  EXPECT_THROW(damping_ratio(ContactModel::linear, 0.0), std::invalid_argument);
  EXPECT_THROW(damping_ratio(ContactModel::linear, 1.5), std::invalid_argument);
}

}  // namespace
}  // namespace gs::test
