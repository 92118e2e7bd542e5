#pragma once
// The full contact law of one contact, as seen from particle i: normal force,
// optional cohesion, tangential friction with history and rolling resistance.
// The same function serves particle-particle and particle-wall contacts; what a
// scene does not use is removed at compile time through `Effects`.
#include "contact/normal_force.hpp"
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
};

// Spring history of one contact; unused members are never touched.
template <class Real>
struct ContactSprings {
  Vec3<Real> tangential;  // elastic tangential force f_e [N]
  Vec3<Real> rolling;     // rolling displacement xi_r [m]
};

template <class Real>
struct ContactLoad {
  Vec3<Real> force;   // on particle i
  Vec3<Real> torque;  // on particle i, about its centre
};

template <class Real, ContactModel Model, unsigned Effects>
GS_HD GS_INLINE ContactLoad<Real> contact_load(const PairParams<Real>& p, const ContactKinematics<Real>& c,
                                               ContactSprings<Real>& springs, Real dt) {
  const Real normal_speed = dot(c.velocity, c.normal);
  const Real overlap_rate = -normal_speed;
  Real normal_force;  // repulsive, >= 0: the clamped spring-dashpot
  [[maybe_unused]] Real root_mass = 0;           // linear
  [[maybe_unused]] HertzContact<Real> hertz{};  // Hertz-Mindlin
  if constexpr (Model == ContactModel::linear) {
    root_mass = std::sqrt(c.effective_mass);
    normal_force = linear_normal_force(p, c.overlap, overlap_rate, root_mass);
  } else {
    hertz = hertz_contact(c.overlap, c.effective_mass, c.effective_radius);
    normal_force = hertz_normal_force(p, c.overlap, overlap_rate, hertz);
  }
  ContactLoad<Real> load;
  Real total_normal = normal_force;  // cohesion, the only attraction, comes after the clamp
  if constexpr ((Effects & kCohesion) != 0) total_normal -= cohesion_force(p, c.overlap, c.effective_radius);
  load.force = c.normal * total_normal;

  if constexpr ((Effects & kFriction) != 0) {
    const Vec3<Real> tangential_velocity = mul_add(c.normal, -normal_speed, c.velocity);
    TangentialCoefficients<Real> t;
    if constexpr (Model == ContactModel::linear) {
      t = linear_tangential_coefficients(p, root_mass);
    } else {
      t = mindlin_tangential_coefficients(p, hertz);
    }
    const Vec3<Real> f_t = tangential_force(springs.tangential, c.normal, tangential_velocity, t.stiffness,
                                            t.damping, p.friction, normal_force, dt);
    load.force += f_t;
    load.torque = cross(c.normal * (-c.lever), f_t);
  }
  if constexpr ((Effects & kRollingResistance) != 0) {
    const Vec3<Real> spin = c.normal * dot(c.angular_velocity, c.normal);  // twisting is not resisted
    const Vec3<Real> rolling_velocity = (c.angular_velocity - spin) * c.effective_radius;
    load.torque += rolling_torque(springs.rolling, c.normal, rolling_velocity, p.stiffness_rolling,
                                  p.rolling_friction, normal_force, c.effective_radius, dt);
  }
  return load;
}

}  // namespace gs
