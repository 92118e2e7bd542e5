#pragma once
#include "scene/scene.hpp"

namespace gs {

// Mass of a sphere of radius r and density rho (a particle's stored mass is
// this, rounded to fp32).
double sphere_mass(double r, double rho);

// Effective moduli of two Hertzian materials: 1/E* = sum (1 - nu^2)/E and
// 1/G* = sum 2 (2 - nu)(1 + nu)/E.
double effective_youngs_modulus(const MaterialSpec& a, const MaterialSpec& b);
double effective_shear_modulus(const MaterialSpec& a, const MaterialSpec& b);

// Duration of a lone contact of the clamped linear spring-dashpot
// (contact/normal_force.hpp) whose restitution is e: the force returns to zero
// when omega0 sqrt(1 - zeta^2) t = 2 arccos(zeta), before the overlap does
// (zeta from contact/restitution.hpp; overdamped: 2 arccosh(zeta) over
// omega0 sqrt(zeta^2 - 1)).
double linear_contact_time(double stiffness_normal, double effective_mass, double restitution);

// Rayleigh time of a sphere of radius r: the time scale of Hertzian contacts.
double rayleigh_time(double radius, double density, double youngs_modulus, double poisson_ratio);

// Shortest contact time over every pair of materials that can touch, using the
// smallest particles of each material present in the scene (linear model: the
// clamped spring-dashpot's contact duration; Hertz-Mindlin: the Rayleigh
// time). It is the unit of fraction_of_contact_time; the largest step accepted
// is contact/stable_step.hpp's.
double critical_contact_time(const SceneSpec& scene);

}  // namespace gs
