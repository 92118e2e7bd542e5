#pragma once
// Velocity Verlet (kick-drift-kick), equivalent to the seed's position Verlet
// (Eqs. 3-5) but self-starting and with velocities at whole steps, which the
// velocity-dependent damping and friction need. Rotation: the same half kicks
// for the angular velocity (Eqs. 6-7 with a symmetric split), and the
// orientation quaternion advanced by q' = 1/2 (0, omega) q.
#include <cmath>

#include "core/fault.hpp"
#include "core/particle_fields.hpp"
#include "core/domain_faces.hpp"

namespace gs {

struct IntegrationParams {
  double dt;
  Vec3d gravity;
  Vec3d domain_lo, domain_hi;
  double max_displacement;  // per step; half a cell
  long long step;
  bool fp32_state;  // precision fp32_full: the state is kept on the fp32 grid
  // Domain faces a particle may leave through (bits of core/domain_faces.hpp):
  // beyond them it is removed after the drift, not a fault.
  unsigned open_faces = 0;
};

// The nearest fp32 values: what a code that stores the state in fp32 keeps.
GS_HD GS_INLINE Vec3d on_fp32_grid(const Vec3d& v) {
  return Vec3d(double(float(v.x)), double(float(v.y)), double(float(v.z)));
}

GS_HD GS_INLINE void advance_orientation(Quaternion& q, const Vec3d& omega, double dt) {
  const float hx = float(0.5 * dt * omega.x), hy = float(0.5 * dt * omega.y), hz = float(0.5 * dt * omega.z);
  Quaternion r{q.w - hx * q.x - hy * q.y - hz * q.z, q.x + hx * q.w + hy * q.z - hz * q.y,
               q.y - hx * q.z + hy * q.w + hz * q.x, q.z + hx * q.y - hy * q.x + hz * q.w};
  const float inv = 1.0f / std::sqrt(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
  q = Quaternion{r.w * inv, r.x * inv, r.y * inv, r.z * inv};
}

// Half kick of velocities by the forces of the current positions.
template <class Real>
struct HalfKick {
  Vec3d* velocity;
  Vec3d* angular_velocity;
  const Vec3<Real>* force;
  const Vec3<Real>* torque;  // null when nothing makes torques (frictionless)
  const float* mass;
  const float* inertia;
  double half_dt;
  Vec3d gravity;
  bool fp32_state;

  GS_HD void operator()(Index i) const {
    velocity[i] += (Vec3d(force[i]) * (1.0 / double(mass[i])) + gravity) * half_dt;
    if (torque) angular_velocity[i] += Vec3d(torque[i]) * (half_dt / double(inertia[i]));
    if (fp32_state) {
      velocity[i] = on_fp32_grid(velocity[i]);
      angular_velocity[i] = on_fp32_grid(angular_velocity[i]);
    }
  }
};

// Half kick, then drift of positions and orientation over a whole step, and
// the checks that stop a run cleanly instead of letting it blow up.
template <class Real>
struct KickDrift {
  HalfKick<Real> kick;
  Vec3d* position;
  Quaternion* orientation;
  const ParticleId* id;
  IntegrationParams p;
  Fault* fault;

  GS_HD void operator()(Index i) const {
    kick(i);
    const Vec3d v = kick.velocity[i];
    const Vec3d step = v * p.dt;
    Vec3d& x = position[i];
    x += step;
    if (p.fp32_state) x = on_fp32_grid(x);
    advance_orientation(orientation[i], kick.angular_velocity[i], p.dt);
    if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && std::isfinite(v.x) &&
          std::isfinite(v.y) && std::isfinite(v.z))) {
      report_fault(fault, kFaultNotFinite, id[i], p.step);
    } else if ((faces_beyond(x, p.domain_lo, p.domain_hi) & ~p.open_faces) != 0) {
      report_fault(fault, kFaultLeftDomain, id[i], p.step);
    } else if (norm2(step) > p.max_displacement * p.max_displacement) {
      report_fault(fault, kFaultTooFast, id[i], p.step);
    }
  }
};

}  // namespace gs
