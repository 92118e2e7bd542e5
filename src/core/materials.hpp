#pragma once
#include "core/hd.hpp"

namespace gs {

// Contact parameters of one pair of materials, already reduced to what the
// force laws use. Real is the force precision.
template <class Real>
struct PairParams {
  Real stiffness_normal;      // linear: k_n [N/m]
  Real stiffness_tangential;  // linear: k_t [N/m]; Hertz-Mindlin: unused (from shear_modulus_eff)
  Real stiffness_rolling;     // k_r [N/m], rolling spring (both models, constant over a contact)
  // Dashpots, with zeta >= 0 from the restitution (contact/restitution.hpp,
  // for the clamped normal force; above 1 for e < exp(-2)): gamma = factor *
  // sqrt(m_eff) (linear) or factor * sqrt(a m_eff) (Hertz-Mindlin, a =
  // sqrt(R* delta)). The constant part of the root is taken once per pair of
  // materials, so a contact takes one square root for both of its dashpots.
  Real damping_factor_normal;      // linear: 2 zeta sqrt(k_n); Hertz: 2 sqrt(5/6) zeta sqrt(2 E*)
  Real damping_factor_tangential;  // linear: 2 zeta sqrt(k_t); Mindlin: 2 sqrt(5/6) zeta sqrt(8 G*)
  Real friction;              // Coulomb coefficient mu
  Real rolling_friction;      // dimensionless mu_r: rolling torque cap mu_r R_eff f_n
  Real cohesion;              // cohesion energy density k_c [N/m^2]: f = k_c * contact area
  Real youngs_modulus_eff;    // Hertz: E* [Pa]
  Real shear_modulus_eff;     // Hertz: G* [Pa]
};

// Read-only view of the symmetric pair table, n_materials^2 entries.
template <class Real>
struct PairTable {
  const PairParams<Real>* params;
  int n_materials;
  GS_HD const PairParams<Real>& operator()(int a, int b) const { return params[a * n_materials + b]; }
};

}  // namespace gs
