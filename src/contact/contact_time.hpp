#pragma once
#include "scene/scene.hpp"

namespace gs {

// Mass of a sphere of radius r and density rho (a particle's stored mass is
// this, rounded to fp32).
double sphere_mass(double r, double rho);

// Damping ratio zeta of a linear spring-dashpot whose normal coefficient of
// restitution is e: e = exp(-pi zeta / sqrt(1 - zeta^2)).
double damping_ratio_from_restitution(double restitution);

// Duration of a linear spring-dashpot contact: pi / (omega0 sqrt(1 - zeta^2)).
double linear_contact_time(double stiffness_normal, double effective_mass, double restitution);

// Rayleigh time of a sphere of radius r: the time scale of Hertzian contacts.
double rayleigh_time(double radius, double density, double youngs_modulus, double poisson_ratio);

// Shortest contact time over every pair of materials that can touch, using the
// smallest particles of each material present in the scene (linear model: the
// spring-dashpot period; Hertz-Mindlin: the Rayleigh time).
double critical_contact_time(const SceneSpec& scene);

// Largest time step accepted for a given contact time. Velocity Verlet on a lone
// contact is stable below 0.64 t_c; a particle pressed by many neighbours sees a
// stiffer effective spring, so the limit keeps a margin of ~3.
constexpr double kStableFractionOfContactTime = 0.2;

}  // namespace gs
