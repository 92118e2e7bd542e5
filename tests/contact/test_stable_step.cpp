// The time-step limit (contact/stable_step.hpp) against an independent
// computation: the dynamical matrix of a face-centred cubic packing of equal
// spheres (12 contacts each) with normal, tangential and rolling springs and
// the rotations, and its largest eigenvalue over a grid of wave vectors. Also the lone-contact limit, the
// binding spring's name, and the loader refusing a step above the limit.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "scene/scene_time_step.hpp"
#include "contact/restitution.hpp"
#include "scene/scene_loader.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.001, kDensity = 2500, kStiffness = 1e4;

using Complex = std::complex<double>;
using Matrix6 = std::array<std::array<Complex, 6>, 6>;
using Block = std::array<std::array<double, 6>, 3>;  // a 3 x 6 map from (u, omega) to a relative motion

// Largest eigenvalue of a Hermitian positive semi-definite 6 x 6 matrix by
// power iteration from several starts.
double largest_eigenvalue(const Matrix6& a) {
  double best = 0;
  for (int start = 0; start < 2; ++start) {
    std::array<Complex, 6> x{};
    for (int i = 0; i < 6; ++i) x[i] = Complex(1.0 + 0.1 * i * (start + 1), 0.3 * ((i + start) % 3));
    double lambda = 0;
    for (int it = 0; it < 1500; ++it) {
      std::array<Complex, 6> y{};
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) y[i] += a[i][j] * x[j];
      double norm = 0;
      for (const Complex& v : y) norm += std::norm(v);
      norm = std::sqrt(norm);
      if (norm == 0) break;
      for (int i = 0; i < 6; ++i) x[i] = y[i] / norm;
      lambda = norm;
    }
    best = std::max(best, lambda);
  }
  return best;
}

struct Springs {
  double normal, tangential, rolling, beta_normal, beta_tangential;
};

// M^-1/2 (h^2 K(q) + 2 h C(q)) M^-1/2 of the FCC packing: every contact's
// relative motion, as a map of the particle's (u, omega) and its neighbour's,
// weighted by its spring (and dashpot), summed with the neighbour's phase.
Matrix6 fcc_matrix(const Springs& k, double h, const std::array<double, 3>& q) {
  const double m = 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius * kDensity, inertia = 0.4 * m * kRadius * kRadius;
  const double scale[6] = {1 / std::sqrt(m), 1 / std::sqrt(m), 1 / std::sqrt(m),
                           1 / std::sqrt(inertia), 1 / std::sqrt(inertia), 1 / std::sqrt(inertia)};
  Matrix6 a{};
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        if (std::abs(dx) + std::abs(dy) + std::abs(dz) != 2) continue;
        const double s = 1 / std::sqrt(2.0);
        const double n[3] = {-dx * s, -dy * s, -dz * s};  // from the neighbour to the particle
        const double d[3] = {2 * kRadius * dx * s, 2 * kRadius * dy * s, 2 * kRadius * dz * s};
        const Complex phase = std::exp(Complex(0, q[0] * d[0] + q[1] * d[1] + q[2] * d[2]));
        // Relative motions: normal (u_i - u_j).n n; slip P(u_i - u_j) + r (omega_i + omega_j) x n;
        // rolling R* P (omega_i - omega_j), R* = r / 2.
        Block normal_i{}, normal_j{}, slip_i{}, slip_j{}, roll_i{}, roll_j{};
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const double nn = n[r] * n[c], p = (r == c) - nn;
            normal_i[r][c] = nn, normal_j[r][c] = -nn;
            slip_i[r][c] = p, slip_j[r][c] = -p;
            roll_i[r][3 + c] = 0.5 * kRadius * p, roll_j[r][3 + c] = -0.5 * kRadius * p;
          }
        // (omega x n)_r = sum_c eps(r, c, l) omega_c n_l
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            double cross = 0;
            for (int l = 0; l < 3; ++l) {
              const int e = (r == c || c == l || r == l) ? 0 : ((c - r + 3) % 3 == 1 ? 1 : -1);
              cross += e * n[l];
            }
            slip_i[r][3 + c] = kRadius * cross, slip_j[r][3 + c] = kRadius * cross;
          }
        const struct {
          const Block &bi, &bj;
          double weight;
        } families[] = {{normal_i, normal_j, h * h * k.normal + 2 * h * k.beta_normal * k.normal},
                        {slip_i, slip_j, h * h * k.tangential + 2 * h * k.beta_tangential * k.tangential},
                        {roll_i, roll_j, h * h * k.rolling}};
        // Energy of the contact, split between its two particles: each particle
        // sees B_i^T B_i + B_i^T B_j e^{iqd}, and the sum over its 12
        // neighbours counts every contact from both sides.
        for (const auto& f : families)
          for (int r = 0; r < 6; ++r)
            for (int c = 0; c < 6; ++c) {
              Complex sum = 0;
              for (int l = 0; l < 3; ++l) sum += f.bi[l][r] * (f.bi[l][c] + f.bj[l][c] * phase);
              a[r][c] += 0.5 * f.weight * sum * scale[r] * scale[c];
            }
      }
  // The half above and its Hermitian transpose (the neighbour's view).
  Matrix6 full{};
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) full[r][c] = a[r][c] + std::conj(a[c][r]);
  return full;
}

double fcc_largest(const Springs& k, double h) {
  double best = 0;
  const int nq = 4;  // 0, the zone boundary (X) and between, in each direction
  const double step = 2 * M_PI / (nq * 2 * kRadius / std::sqrt(2.0));
  for (int i = 0; i < nq; ++i)
    for (int j = 0; j < nq; ++j)
      for (int l = 0; l < nq; ++l) best = std::max(best, largest_eigenvalue(fcc_matrix(k, h, {i * step, j * step, l * step})));
  return best;
}

SceneSpec bed(double restitution, double tangential_ratio, unsigned effects) {
  SceneSpec s = base_scene(kDensity, kStiffness, restitution, 0.5);
  s.effects = effects;
  s.pairs[0].stiffness_tangential = tangential_ratio * kStiffness;
  s.pairs[0].stiffness_rolling = tangential_ratio * kStiffness;
  s.pairs[0].rolling_friction = 0.1;
  s.particles.push_back(particle(0, kRadius, {0, 0, 0}));
  return s;
}

Springs linear_springs(const SceneSpec& s, unsigned effects) {
  const PairSpec& p = s.pairs[0];
  const double m_eff = 0.5 * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius * kDensity;
  const double zeta = damping_ratio(ContactModel::linear, p.restitution);
  return {p.stiffness_normal, (effects & kFriction) ? p.stiffness_tangential : 0.0,
          (effects & kRollingResistance) ? p.stiffness_rolling : 0.0,
          2 * zeta * std::sqrt(m_eff / p.stiffness_normal), 2 * zeta * std::sqrt(m_eff / p.stiffness_tangential)};
}

// At the limit, the FCC packing's largest eigenvalue of M^-1/2 (h^2 K + 2 h C)
// M^-1/2 is 4 (its stiffest mode on the edge of stability), for the
// frictionless, frictional and rolling beds over restitutions and k_t / k_n.
TEST(StableStep, MatchesTheFaceCentredCubicPacking) {
  for (const unsigned effects : {0u, unsigned(kFriction), unsigned(kFriction | kRollingResistance)})
    for (const double e : {0.1, 0.5, 0.9, 1.0})
      for (const double ratio : {2.0 / 7.0, 1.0}) {
        const SceneSpec s = bed(e, ratio, effects);
        const double limit = stable_time_step(s).time_step;
        SCOPED_TRACE("effects " + std::to_string(effects) + ", e " + std::to_string(e) + ", k_t/k_n " +
                     std::to_string(ratio));
        EXPECT_NEAR(fcc_largest(linear_springs(s, effects), limit), 4.0, 4e-3);
      }
}

// A lone undamped contact is stable below 2 / omega; the dense bed's normal
// modes have omega twice the lone contact's (lambda = 4 k / m*).
TEST(StableStep, ModeLimits) {
  EXPECT_DOUBLE_EQ(stable_step_of_mode(4.0, 0), 1.0);
  const double lambda = 3.0, beta = 0.2, h = stable_step_of_mode(lambda, beta);
  EXPECT_NEAR(lambda * (h * h + 2 * h * beta), 4.0, 1e-12);
  const SceneSpec s = bed(1.0, 2.0 / 7.0, 0);
  const double m_eff = 0.5 * sphere_mass(kRadius, kDensity);
  EXPECT_NEAR(stable_time_step(s).time_step, 1 / std::sqrt(kStiffness / m_eff), 1e-12);
}

TEST(StableStep, NamesTheBindingSpring) {
  EXPECT_EQ(stable_time_step(bed(0.5, 2.0 / 7.0, 0)).binding, "normal spring of [m, m]");
  EXPECT_EQ(stable_time_step(bed(0.5, 2.0 / 7.0, kFriction)).binding, "tangential spring (with rotation) of [m, m]");
  SceneSpec stiff_rolling = bed(0.5, 2.0 / 7.0, kFriction | kRollingResistance);
  stiff_rolling.pairs[0].stiffness_rolling = 100 * kStiffness;
  EXPECT_EQ(stable_time_step(stiff_rolling).binding, "rolling spring of [m, m]");
  SceneSpec no_friction = bed(0.5, 2.0 / 7.0, kFriction);
  no_friction.pairs[0].friction = 0;  // no tangential force: the normal spring binds
  EXPECT_EQ(stable_time_step(no_friction).binding, "normal spring of [m, m]");
}

// A wall is an immobile partner: with the same springs it binds less than a
// sphere (half the lambda), so a wall pair stiffer than the sphere pair by
// more than 2 binds.
TEST(StableStep, WallPairs) {
  SceneSpec s = bed(0.5, 2.0 / 7.0, 0);
  MaterialSpec steel;
  steel.name = "steel";
  steel.density = 7800;
  s.materials.push_back(steel);
  PairSpec wall = s.pairs[0];
  wall.material_b = 1;
  wall.stiffness_normal = 3 * kStiffness;
  s.pairs.push_back(wall);
  EXPECT_EQ(stable_time_step(s).binding, "normal spring of [m, steel]");
  s.pairs[1].stiffness_normal = 1.5 * kStiffness;
  EXPECT_EQ(stable_time_step(s).binding, "normal spring of [m, m]");
}

std::string scene_text(const std::string& time_step) {
  return "domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}\n"
         "gravity: [0, 0, -9.81]\ncontact_model: linear\n"
         "effects: {friction: true, rolling_resistance: false, cohesion: false}\n"
         "materials:\n  - {name: glass, density: 2500}\n"
         "pairs:\n  - {materials: [glass, glass], stiffness_normal: 10000, restitution: 0.3, friction: 0.5}\n"
         "particles:\n  - lattice: {material: glass, radius: 0.001, min: [-0.005, -0.005, -0.005], "
         "max: [0.005, 0.005, 0.005]}\n"
         "time_step: " + time_step + "\nduration: 0.01\n";
}

// The bed: 2 mm spheres, k_n = 1e4 N/m, friction, e = 0.3. The old
// limit, 0.2 t_c, erupted; the loader now refuses it, naming the spring.
TEST(StableStep, LoaderRefusesAStepAboveTheLimit) {
  const SceneSpec ok = parse_scene(scene_text("{fraction_of_contact_time: 0.05}"), "ok.yaml");
  EXPECT_NEAR(ok.stable_time_step / ok.contact_time, 0.0741, 5e-4);
  EXPECT_EQ(ok.stable_step_binding, "tangential spring (with rotation) of [glass, glass]");
  try {
    parse_scene(scene_text("{fraction_of_contact_time: 0.2}"), "bad.yaml");
    FAIL() << "0.2 t_c accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.yaml:"), std::string::npos) << what;
    EXPECT_NE(what.find("exceeds the stability limit"), std::string::npos) << what;
    EXPECT_NE(what.find("tangential spring (with rotation) of [glass, glass]"), std::string::npos) << what;
  }
  const SceneSpec at = parse_scene(scene_text("{absolute: " + std::to_string(ok.stable_time_step * (1 - 1e-9)) + "}"),
                                   "at.yaml");
  EXPECT_LE(at.time_step, at.stable_time_step);
}

}  // namespace
}  // namespace gs::test
