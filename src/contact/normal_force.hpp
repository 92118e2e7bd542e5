#pragma once
// Normal contact forces (seed Eq. 8; Hertz-Mindlin as the second model).
// Sign convention: positive = repulsive, along the normal n that points from
// the partner j to the particle i. `overlap_rate` is d(overlap)/dt, positive
// while the spheres approach.
//
// Both spring-dashpots are clamped at zero: a separating contact whose dashpot
// would outweigh its spring does not pull (the surfaces part before the
// overlap closes). Attraction comes only from cohesion, subtracted after the
// clamp (contact_law.hpp). The clamp changes the restitution a damping ratio
// gives; contact/restitution.hpp derives zeta for the clamped law.
#include <cmath>

#include "core/hd.hpp"
#include "core/materials.hpp"

namespace gs {

// max(0, f), written out so that it is the same on host and device.
template <class Real>
GS_HD GS_INLINE Real repulsive_part(Real f) {
  return f > Real(0) ? f : Real(0);
}

// Linear spring-dashpot (Luding 1998): f_n = max(0, k_n delta + gamma_n delta'),
// gamma_n = 2 zeta sqrt(m_eff k_n), zeta from the restitution coefficient.
// `damping_root` is the contact's sqrt(m_eff), shared with the tangential dashpot.
template <class Real>
GS_HD GS_INLINE Real linear_normal_force(const PairParams<Real>& p, Real overlap, Real overlap_rate,
                                          Real damping_root) {
  const Real gamma_n = p.damping_factor_normal * damping_root;
  return repulsive_part(mul_add(p.stiffness_normal, overlap, gamma_n * overlap_rate));
}

// What the Hertz-Mindlin forces of one contact share: the contact radius
// a = sqrt(R* delta), and sqrt(a m*), the root both dashpots scale with.
template <class Real>
struct HertzContact {
  Real contact_radius;
  Real damping_root;
};

template <class Real>
GS_HD GS_INLINE HertzContact<Real> hertz_contact(Real overlap, Real effective_mass, Real effective_radius) {
  const Real a = std::sqrt(effective_radius * overlap);
  return {a, std::sqrt(a * effective_mass)};
}

// Hertz: f_n = max(0, 4/3 E* sqrt(R*) delta^(3/2) plus Tsuji-type damping
// 2 sqrt(5/6) zeta sqrt(S_n m*) delta'), with S_n = 2 E* sqrt(R* delta).
template <class Real>
GS_HD GS_INLINE Real hertz_normal_force(const PairParams<Real>& p, Real overlap, Real overlap_rate,
                                         const HertzContact<Real>& h) {
  const Real elastic = Real(4) / Real(3) * p.youngs_modulus_eff * h.contact_radius * overlap;
  return repulsive_part(mul_add(p.damping_factor_normal * h.damping_root, overlap_rate, elastic));
}

// Tangential stiffness and damping coefficient of the contact.
template <class Real>
struct TangentialCoefficients {
  Real stiffness;
  Real damping;
};

// Linear: k_t, gamma_t = 2 zeta sqrt(m_eff k_t); `damping_root` is sqrt(m_eff).
template <class Real>
GS_HD GS_INLINE TangentialCoefficients<Real> linear_tangential_coefficients(const PairParams<Real>& p,
                                                                             Real damping_root) {
  return {p.stiffness_tangential, p.damping_factor_tangential * damping_root};
}

// Mindlin: S_t = 8 G* sqrt(R* delta), damping 2 sqrt(5/6) zeta sqrt(S_t m*).
template <class Real>
GS_HD GS_INLINE TangentialCoefficients<Real> mindlin_tangential_coefficients(const PairParams<Real>& p,
                                                                              const HertzContact<Real>& h) {
  return {Real(8) * p.shear_modulus_eff * h.contact_radius, p.damping_factor_tangential * h.damping_root};
}

// Cohesion (simplified JKR): an attraction proportional to the contact area
// pi a^2 = pi R* delta, scaled by the cohesion energy density k_c.
template <class Real>
GS_HD GS_INLINE Real cohesion_force(const PairParams<Real>& p, Real overlap, Real effective_radius) {
  return p.cohesion * Real(3.14159265358979323846) * effective_radius * overlap;
}

}  // namespace gs
