#pragma once
// Contact durations: the unit of a scene's fraction_of_contact_time.
#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/contact_scene.hpp"
#include "core/materials.hpp"

namespace gs {

// Mass of a sphere of radius r and density rho (a particle's stored mass is
// this, rounded to fp32).
double sphere_mass(double r, double rho);

// Effective moduli of two Hertzian materials: 1/E* = sum (1 - nu^2)/E and
// 1/G* = sum 2 (2 - nu)(1 + nu)/E.
double effective_youngs_modulus(const MaterialSpec& a, const MaterialSpec& b);
double effective_shear_modulus(const MaterialSpec& a, const MaterialSpec& b);

// Duration of a lone contact of the clamped linear spring-dashpot
// (contact/models/linear_spring_dashpot.hpp) whose restitution is e: the force returns to zero
// when omega0 sqrt(1 - zeta^2) t = 2 arccos(zeta), before the overlap does
// (zeta from contact/restitution.hpp; overdamped: 2 arccosh(zeta) over
// omega0 sqrt(zeta^2 - 1)).
double linear_contact_time(double stiffness_normal, double effective_mass, double restitution);

// Rayleigh time of a sphere of radius r: the time scale of Hertzian contacts.
double rayleigh_time(double radius, double density, double youngs_modulus, double poisson_ratio);

// The shortest time(pair, m*) over the pairs of materials that can touch, for
// the smallest particles of each (r: the smallest radius of each material's
// particles, infinite for a material without particles, a wall's: a partner
// of infinite mass).
template <class PairTime>
double shortest_over_pairs(const std::vector<MaterialSpec>& materials, const std::vector<PairSpec>& pairs,
                           const std::vector<double>& r, PairTime time) {
  double t = INFINITY;
  for (const PairSpec& pair : pairs) {
    const int a = pair.material_a, b = pair.material_b;
    const bool a_moves = std::isfinite(r[a]), b_moves = std::isfinite(r[b]);
    if (!a_moves && !b_moves) continue;
    double m_eff;
    if (a_moves && b_moves) {
      const double ma = sphere_mass(r[a], materials[a].density);
      const double mb = sphere_mass(r[b], materials[b].density);
      m_eff = ma * mb / (ma + mb);
    } else {
      const int m = a_moves ? a : b;
      m_eff = sphere_mass(r[m], materials[m].density);
    }
    t = std::min(t, double(time(pair, m_eff)));
  }
  return t;
}

// The shortest contact time of the scene's model (its critical_contact_time,
// contact/contact_model.hpp) for the smallest particles of each material
// present. It is the unit of fraction_of_contact_time; the largest step
// accepted is contact/stable_step.hpp's.
double critical_contact_time(const ContactScene& scene);

}  // namespace gs
