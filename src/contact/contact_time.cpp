#include "contact/contact_time.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gs {

double damping_ratio_from_restitution(double e) {
  const double log_e = std::log(e);
  return -log_e / std::sqrt(M_PI * M_PI + log_e * log_e);
}

double linear_contact_time(double kn, double m_eff, double e) {
  const double zeta = damping_ratio_from_restitution(e);
  return M_PI / (std::sqrt(kn / m_eff) * std::sqrt(1.0 - zeta * zeta));
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
