#pragma once
// The full contact law of one contact, as seen from particle i: the model's
// normal force, optional cohesion, tangential friction with history and
// rolling resistance. The same function serves particle-particle and
// particle-wall contacts; what a scene does not use is removed at compile
// time through `Model` and `Effects`.
//
// Sign convention: a positive normal force is repulsive, along the normal n
// that points from the partner j to particle i; `overlap_rate` is
// d(overlap)/dt, positive while the spheres approach. Every normal law is
// clamped at zero (a separating contact whose dashpot would outweigh its
// spring does not pull: the surfaces part before the overlap closes);
// attraction comes only from cohesion, subtracted after the clamp. The clamp
// changes the restitution a damping ratio gives; contact/restitution.hpp
// derives zeta for the clamped laws.
#include "contact/contact_model.hpp"
#include "contact/tangential_spring.hpp"
#include "core/types.hpp"

namespace gs {

template <class Real>
struct ContactKinematics {
  Real overlap;                // delta > 0
  Vec3<Real> normal;           // unit, from the partner towards particle i
  Vec3<Real> velocity;         // v_i - v_j of the material points at the contact
  Vec3<Real> angular_velocity; // omega_i - omega_j
  Real effective_mass;         // m_i m_j / (m_i + m_j); m_i against a wall
  Real effective_radius;       // r_i r_j / (r_i + r_j); r_i against a wall
  Real lever;                  // distance from the centre of i to the contact point
  Real partner_lever;          // from the centre of j to it (particle pairs only)
};

template <class Real>
struct ContactLoad {
  Vec3<Real> force;   // on particle i
  Vec3<Real> torque;  // on particle i, about its centre
};

// Cohesion (simplified JKR): an attraction proportional to the contact area
// pi a^2 = pi R* delta, scaled by the cohesion energy density k_c.
template <class Real>
GS_HD GS_INLINE Real cohesion_force(Real energy_density, Real overlap, Real effective_radius) {
  return energy_density * Real(3.14159265358979323846) * effective_radius * overlap;
}

// What the law gives one contact, as seen from particle i, before it becomes
// i's load: computed once per pair, it gives the partner's load too
// (mirrored(), then load_on() with the partner's normal and lever).
template <class Real>
struct ContactForces {
  Vec3<Real> force;           // on i: the normal force (cohesion included) plus the tangential one
  Vec3<Real> tangential;      // the tangential (friction) force on i
  Vec3<Real> rolling_torque;  // the rolling resistance's couple on i
};

// The law of one contact; updates its history `state`.
template <class Real, class Model, unsigned Effects>
GS_HD GS_INLINE ContactForces<Real> contact_forces(const PairParams<Real, Model>& p, const ContactKinematics<Real>& c,
                                                   ContactState<Real>& state, Real dt) {
  const Real normal_speed = dot(c.velocity, c.normal);
  const Real overlap_rate = -normal_speed;
  const auto local = Model::local(p.model, c.overlap, c.effective_mass, c.effective_radius);
  const Real normal_force = Model::normal_force(p.model, c.overlap, overlap_rate, local, state);  // >= 0
  ContactForces<Real> f;
  Real total_normal = normal_force;  // cohesion, the only attraction, comes after the clamp
  if constexpr ((Effects & kCohesion) != 0) total_normal -= cohesion_force(p.cohesion, c.overlap, c.effective_radius);
  f.force = c.normal * total_normal;

  if constexpr ((Effects & kFriction) != 0) {
    const Vec3<Real> tangential_velocity = mul_add(c.normal, -normal_speed, c.velocity);
    const TangentialCoefficients<Real> t = Model::tangential(p.model, local);
    f.tangential = tangential_force(state.tangential, c.normal, tangential_velocity, t.stiffness, t.damping,
                                    p.friction, normal_force, dt);
    f.force += f.tangential;
  }
  if constexpr ((Effects & kRollingResistance) != 0) {
    const Vec3<Real> spin = c.normal * dot(c.angular_velocity, c.normal);  // twisting is not resisted
    const Vec3<Real> rolling_velocity = (c.angular_velocity - spin) * c.effective_radius;
    f.rolling_torque = rolling_torque(state.rolling, c.normal, rolling_velocity, p.stiffness_rolling,
                                      p.rolling_friction, normal_force, c.effective_radius, dt);
  }
  return f;
}

// The load on a sphere whose contact has forces f, normal `normal` (towards
// the sphere) and lever `lever` (from its centre to the contact point).
template <class Real, unsigned Effects>
GS_HD GS_INLINE ContactLoad<Real> load_on(const ContactForces<Real>& f, const Vec3<Real>& normal, Real lever) {
  ContactLoad<Real> load;
  load.force = f.force;
  if constexpr ((Effects & kFriction) != 0) load.torque = cross(normal * (-lever), f.tangential);
  if constexpr ((Effects & kRollingResistance) != 0) load.torque += f.rolling_torque;
  return load;
}

// The same forces seen from the partner: every one negated (exactly, as the
// partner's own computation gives them: force_kernel.hpp, particle_kinematics).
template <class Real>
GS_HD GS_INLINE ContactForces<Real> mirrored(const ContactForces<Real>& f) {
  return {-f.force, -f.tangential, -f.rolling_torque};
}

template <class Real, class Model, unsigned Effects>
GS_HD GS_INLINE ContactLoad<Real> contact_load(const PairParams<Real, Model>& p, const ContactKinematics<Real>& c,
                                               ContactState<Real>& state, Real dt) {
  return load_on<Real, Effects>(contact_forces<Real, Model, Effects>(p, c, state, dt), c.normal, c.lever);
}

}  // namespace gs
