#pragma once
// Tangential friction with history (seed Eqs. 9-11) and rolling resistance,
// both as springs integrated over the life of a contact and capped Coulomb-like.
#include "core/hd.hpp"
#include "core/vec3.hpp"

namespace gs {

// Keep a spring in the current tangent plane: the contact frame turns as the
// particles move, so the stored displacement is rotated (projected and
// rescaled to its old length) rather than merely projected.
template <class Real>
GS_HD GS_INLINE Vec3<Real> rotate_into_tangent_plane(const Vec3<Real>& spring, const Vec3<Real>& normal) {
  const Real old_length2 = norm2(spring);
  if (old_length2 == Real(0)) return spring;
  const Vec3<Real> projected = mul_add(normal, -dot(spring, normal), spring);
  const Real new_length2 = norm2(projected);
  if (new_length2 == Real(0)) return Vec3<Real>();
  return projected * std::sqrt(old_length2 / new_length2);
}

// Sliding friction: xi += v_t dt; f_t = -k_t xi - gamma_t v_t, capped at
// mu |f_n|; when sliding the spring is reset to the length the cap allows.
// Returns the tangential force on the particle; updates `spring` in place.
template <class Real>
GS_HD GS_INLINE Vec3<Real> tangential_force(Vec3<Real>& spring, const Vec3<Real>& normal,
                                            const Vec3<Real>& tangential_velocity, Real stiffness, Real damping,
                                            Real friction, Real normal_force, Real dt) {
  spring = mul_add(tangential_velocity, dt, rotate_into_tangent_plane(spring, normal));
  Vec3<Real> force = -mul_add(spring, stiffness, tangential_velocity * damping);
  const Real cap = friction * std::fabs(normal_force);
  const Real magnitude2 = norm2(force);
  if (magnitude2 > cap * cap) {
    force = force * (cap / std::sqrt(magnitude2));
    spring = -mul_add(tangential_velocity, damping, force) * (Real(1) / stiffness);
  }
  return force;
}

// Rolling resistance "in analogy to sliding friction": an angular spring on
// the relative rolling rotation, stored as a displacement xi_r = R* theta_r,
// with force k_r xi_r capped at mu_r |f_n|; the torque on the particle is
// -R* k_r xi_r. At the cap a rolling sphere feels the constant torque
// mu_r R* |f_n|. `rolling_velocity` is R* (omega_i - omega_j) in the tangent plane.
template <class Real>
GS_HD GS_INLINE Vec3<Real> rolling_torque(Vec3<Real>& spring, const Vec3<Real>& normal,
                                          const Vec3<Real>& rolling_velocity, Real stiffness,
                                          Real rolling_friction, Real normal_force, Real effective_radius, Real dt) {
  spring = mul_add(rolling_velocity, dt, rotate_into_tangent_plane(spring, normal));
  Vec3<Real> force = spring * stiffness;
  const Real cap = rolling_friction * std::fabs(normal_force);
  const Real magnitude2 = norm2(force);
  if (magnitude2 > cap * cap) {
    force = force * (cap / std::sqrt(magnitude2));
    spring = force * (Real(1) / stiffness);
  }
  return -(force * effective_radius);
}

}  // namespace gs
