#pragma once
// Tangential friction with history (seed Eqs. 9-11, in the incremental form of
// Mindlin's law) and rolling resistance, both springs carried over the life of
// a contact and capped Coulomb-like.
#include "core/hd.hpp"
#include "core/vec3.hpp"

namespace gs {

// Keep a stored spring vector in the current tangent plane: the contact frame
// turns as the particles move, so the vector is rotated (projected and
// rescaled to its old magnitude) rather than merely projected.
template <class Real>
GS_HD GS_INLINE Vec3<Real> rotate_into_tangent_plane(const Vec3<Real>& spring, const Vec3<Real>& normal) {
  const Real old_length2 = norm2(spring);
  if (old_length2 == Real(0)) return spring;
  const Vec3<Real> projected = mul_add(normal, -dot(spring, normal), spring);
  const Real new_length2 = norm2(projected);
  if (new_length2 == Real(0)) return Vec3<Real>();
  return projected * std::sqrt(old_length2 / new_length2);
}

// Sliding friction, incremental: the history is the elastic tangential force
// f_e [N] (not a displacement), so that a stiffness that changes over the
// contact (Mindlin's k_t = 8 G* a grows with the overlap) scales only the
// increments it acts on:
//   f_e <- rotate(f_e) - k_t v_t dt,   f_t = f_e - gamma_t v_t,
//   if |f_t| > mu f_n:  f_t <- mu f_n f_t / |f_t|,  f_e <- f_t   (sliding).
// f_n is the clamped repulsive normal force (cohesion excluded). In sliding the
// stored force is the Coulomb force itself, no dashpot part: the force stays
// mu f_n against the slip for as long as the contact slides, whatever k_t and
// gamma_t do. Returns f_t on the particle; updates `elastic_force` in place.
template <class Real>
GS_HD GS_INLINE Vec3<Real> tangential_force(Vec3<Real>& elastic_force, const Vec3<Real>& normal,
                                            const Vec3<Real>& tangential_velocity, Real stiffness, Real damping,
                                            Real friction, Real normal_force, Real dt) {
  elastic_force = mul_add(tangential_velocity, -stiffness * dt, rotate_into_tangent_plane(elastic_force, normal));
  Vec3<Real> force = mul_add(tangential_velocity, -damping, elastic_force);
  const Real cap = friction * normal_force;
  const Real magnitude2 = norm2(force);
  if (magnitude2 > cap * cap) {
    force = force * (cap / std::sqrt(magnitude2));
    elastic_force = force;
  }
  return force;
}

// Rolling resistance "in analogy to sliding friction": an angular spring on
// the relative rolling rotation, stored as a displacement xi_r = R* theta_r,
// with force k_r xi_r capped at mu_r f_n (f_n the clamped repulsive normal
// force); the torque on the particle is -R* k_r xi_r. k_r is the pair's
// stiffness_rolling in all three models, constant over the contact, so the history
// can stay a displacement. At the cap a rolling sphere feels the constant
// torque mu_r R* f_n. `rolling_velocity` is R* (omega_i - omega_j) in the
// tangent plane.
template <class Real>
GS_HD GS_INLINE Vec3<Real> rolling_torque(Vec3<Real>& spring, const Vec3<Real>& normal,
                                          const Vec3<Real>& rolling_velocity, Real stiffness,
                                          Real rolling_friction, Real normal_force, Real effective_radius, Real dt) {
  spring = mul_add(rolling_velocity, dt, rotate_into_tangent_plane(spring, normal));
  Vec3<Real> force = spring * stiffness;
  const Real cap = rolling_friction * normal_force;
  const Real magnitude2 = norm2(force);
  if (magnitude2 > cap * cap) {
    force = force * (cap / std::sqrt(magnitude2));
    spring = force * (Real(1) / stiffness);
  }
  return -(force * effective_radius);
}

}  // namespace gs
