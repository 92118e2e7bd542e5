#include "contact/contact_time.hpp"

#include "contact/contact_models.hpp"
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


double sphere_mass(double r, double rho) { return 4.0 / 3.0 * M_PI * r * r * r * rho; }

double critical_contact_time(const ContactScene& s) {
  return with_contact_model(s.model, [&](auto model) {
    return decltype(model)::critical_contact_time(s.materials, s.pairs, s.smallest_radius);
  });
}

}  // namespace gs
