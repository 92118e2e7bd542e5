#pragma once
// Normal contact forces (seed Eq. 8; Hertz-Mindlin as the second model).
// Sign convention: positive = repulsive, along the normal n that points from
// the partner j to the particle i. `overlap_rate` is d(overlap)/dt, positive
// while the spheres approach.
#include <cmath>

#include "core/hd.hpp"
#include "core/materials.hpp"

namespace gs {

// Linear spring-dashpot (Luding 1998): f_n = k_n delta + gamma_n delta',
// gamma_n = 2 zeta sqrt(m_eff k_n), zeta from the restitution coefficient.
template <class Real>
GS_HD GS_INLINE Real linear_normal_force(const PairParams<Real>& p, Real overlap, Real overlap_rate,
                                          Real effective_mass) {
  const Real gamma_n = Real(2) * p.damping_ratio * std::sqrt(effective_mass * p.stiffness_normal);
  return p.stiffness_normal * overlap + gamma_n * overlap_rate;
}

// Hertz: f_n = 4/3 E* sqrt(R*) delta^(3/2) plus Tsuji-type damping
// 2 sqrt(5/6) zeta sqrt(S_n m*) delta', with S_n = 2 E* sqrt(R* delta).
template <class Real>
GS_HD GS_INLINE Real hertz_normal_force(const PairParams<Real>& p, Real overlap, Real overlap_rate,
                                         Real effective_mass, Real effective_radius) {
  const Real contact_radius = std::sqrt(effective_radius * overlap);  // a = sqrt(R* delta)
  const Real s_n = Real(2) * p.youngs_modulus_eff * contact_radius;
  const Real elastic = Real(4) / Real(3) * p.youngs_modulus_eff * contact_radius * overlap;
  const Real damping = Real(2) * Real(0.9128709291752769) * p.damping_ratio * std::sqrt(s_n * effective_mass);
  return elastic + damping * overlap_rate;
}

// Tangential stiffness and damping coefficient of the contact.
template <class Real>
struct TangentialCoefficients {
  Real stiffness;
  Real damping;
};

template <class Real>
GS_HD GS_INLINE TangentialCoefficients<Real> linear_tangential_coefficients(const PairParams<Real>& p,
                                                                             Real effective_mass) {
  return {p.stiffness_tangential, Real(2) * p.damping_ratio * std::sqrt(effective_mass * p.stiffness_tangential)};
}

// Mindlin: S_t = 8 G* sqrt(R* delta), damping 2 sqrt(5/6) zeta sqrt(S_t m*).
template <class Real>
GS_HD GS_INLINE TangentialCoefficients<Real> mindlin_tangential_coefficients(const PairParams<Real>& p, Real overlap,
                                                                              Real effective_mass,
                                                                              Real effective_radius) {
  const Real s_t = Real(8) * p.shear_modulus_eff * std::sqrt(effective_radius * overlap);
  return {s_t, Real(2) * Real(0.9128709291752769) * p.damping_ratio * std::sqrt(s_t * effective_mass)};
}

// Cohesion (simplified JKR): an attraction proportional to the contact area
// pi a^2 = pi R* delta, scaled by the cohesion energy density k_c.
template <class Real>
GS_HD GS_INLINE Real cohesion_force(const PairParams<Real>& p, Real overlap, Real effective_radius) {
  return p.cohesion * Real(3.14159265358979323846) * effective_radius * overlap;
}

}  // namespace gs
