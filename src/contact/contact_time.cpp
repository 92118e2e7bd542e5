#include "contact/contact_time.hpp"

#include "contact/restitution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gs {

double effective_youngs_modulus(const MaterialSpec& a, const MaterialSpec& b) {
  return 1.0 / ((1 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                (1 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

double effective_shear_modulus(const MaterialSpec& a, const MaterialSpec& b) {
  return 1.0 / (2 * (2 - a.poisson_ratio) * (1 + a.poisson_ratio) / a.youngs_modulus +
                2 * (2 - b.poisson_ratio) * (1 + b.poisson_ratio) / b.youngs_modulus);
}

double linear_contact_time(double kn, double m_eff, double e) {
  const double zeta = damping_ratio(ContactModel::linear, e);
  const double omega0 = std::sqrt(kn / m_eff);
  if (zeta < 1) return 2 * std::acos(zeta) / (omega0 * std::sqrt(1 - zeta * zeta));
  if (zeta == 1) return 2 / omega0;
  return 2 * std::acosh(zeta) / (omega0 * std::sqrt(zeta * zeta - 1));
}

double rayleigh_time(double r, double rho, double youngs, double nu) {
  const double shear = youngs / (2.0 * (1.0 + nu));
  return M_PI * r * std::sqrt(rho / shear) / (0.1631 * nu + 0.8766);
}

namespace {

// Smallest radius of each material among the particles (infinity when absent).
std::vector<double> smallest_radius(const SceneSpec& s) {
  std::vector<double> r(s.materials.size(), std::numeric_limits<double>::infinity());
  for (const auto& p : s.particles) r[p.material] = std::min(r[p.material], p.radius);
  return r;
}

}  // namespace

double sphere_mass(double r, double rho) { return 4.0 / 3.0 * M_PI * r * r * r * rho; }

double critical_contact_time(const SceneSpec& s) {
  const std::vector<double> r = smallest_radius(s);
  double t = std::numeric_limits<double>::infinity();
  if (s.model == ContactModel::hertz_mindlin) {
    for (size_t m = 0; m < s.materials.size(); ++m)
      if (std::isfinite(r[m]))
        t = std::min(t, rayleigh_time(r[m], s.materials[m].density, s.materials[m].youngs_modulus,
                                      s.materials[m].poisson_ratio));
    return t;
  }
  for (const auto& pair : s.pairs) {
    const int a = pair.material_a, b = pair.material_b;
    const bool a_moves = std::isfinite(r[a]), b_moves = std::isfinite(r[b]);
    if (!a_moves && !b_moves) continue;
    // A material without particles is a wall material: infinite mass.
    double m_eff;
    if (a_moves && b_moves) {
      const double ma = sphere_mass(r[a], s.materials[a].density);
      const double mb = sphere_mass(r[b], s.materials[b].density);
      m_eff = ma * mb / (ma + mb);
    } else {
      const int m = a_moves ? a : b;
      m_eff = sphere_mass(r[m], s.materials[m].density);
    }
    t = std::min(t, linear_contact_time(pair.stiffness_normal, m_eff, pair.restitution));
  }
  return t;
}

}  // namespace gs
