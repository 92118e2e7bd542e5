#pragma once
// Velocity Verlet (kick-drift-kick), equivalent to the seed's position Verlet
// (Eqs. 3-5) but self-starting and with velocities at whole steps, which the
// velocity-dependent damping and friction need. Rotation: the same half kicks
// for the angular velocity (Eqs. 6-7 with a symmetric split), and the
// orientation quaternion advanced by q' = 1/2 (0, omega) q.
#include <cmath>

#include "core/fault.hpp"
#include "core/domain_faces.hpp"
#include "core/particle_fields.hpp"
#include "core/periodic_box.hpp"

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
  PeriodicBox box;  // the axes that wrap: a particle crossing their faces comes back at the other
};

// The nearest fp32 value of x. The empty asm makes the host compiler keep the
// float: GCC 12's SLP vectorizer (-O3 -march=x86-64-v3) folded double(float())
// of two lanes into the identity, and positions set up in fp32_full stayed
// off the fp32 grid in x and y (measured 2026-12-03, in Simulation::upload
// and the drift, once their inlining changed).
GS_HD GS_INLINE double on_fp32_grid(double x) {
  float f = float(x);
#if !defined(__CUDA_ARCH__)
  asm("" : "+m"(f));
#endif
  return double(f);
}

// The nearest fp32 values: what a code that stores the state in fp32 keeps.
GS_HD GS_INLINE Vec3d on_fp32_grid(const Vec3d& v) {
  return Vec3d(on_fp32_grid(v.x), on_fp32_grid(v.y), on_fp32_grid(v.z));
}

GS_HD GS_INLINE void advance_orientation(Quaternion& q, const Vec3d& omega, double dt) {
  const float hx = float(0.5 * dt * omega.x), hy = float(0.5 * dt * omega.y), hz = float(0.5 * dt * omega.z);
  Quaternion r{q.w - hx * q.x - hy * q.y - hz * q.z, q.x + hx * q.w + hy * q.z - hz * q.y,
               q.y - hx * q.z + hy * q.w + hz * q.x, q.z + hx * q.y - hy * q.x + hz * q.w};
  const float inv = 1.0f / std::sqrt(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
  q = Quaternion{r.w * inv, r.x * inv, r.y * inv, r.z * inv};
}

// Half kick of velocities by the forces of the current positions. A frozen
// particle (docs/SCENES.md, `frozen`) is not integrated: it stays at rest
// where it was created, whatever pushes on it, and its contacts see it so.
template <class Real>
struct HalfKick {
  Vec3d* velocity;
  Vec3d* angular_velocity;   // null where the run keeps none (nothing spins: no torque either)
  const Vec3<Real>* force;
  const Vec3<Real>* torque;  // null when nothing makes torques (frictionless)
  const float* mass;
  const float* inertia;
  double half_dt;
  Vec3d gravity;
  bool fp32_state;
  const std::uint8_t* frozen = nullptr;  // null unless the run has frozen particles

  GS_HD bool is_frozen(Index i) const { return frozen && frozen[i] != 0; }

  GS_HD void operator()(Index i) const {
    if (is_frozen(i)) return;
    velocity[i] += (Vec3d(force[i]) * (1.0 / double(mass[i])) + gravity) * half_dt;
    if (torque) angular_velocity[i] += Vec3d(torque[i]) * (half_dt / double(inertia[i]));
    if (fp32_state) {
      velocity[i] = on_fp32_grid(velocity[i]);
      if (angular_velocity) angular_velocity[i] = on_fp32_grid(angular_velocity[i]);
    }
  }
};

// Half kick, then drift of positions and orientation over a whole step, and
// the checks that stop a run cleanly instead of letting it blow up. With
// `closing_kick` the last step's closing half kick comes first: it reads the
// same forces (none were computed since), and as the same call twice it
// rounds each kick on its own, so the bits are those of two passes, and the
// velocities and forces are read and written once instead of twice. On a
// periodic axis a particle that crossed a face is wrapped back into the
// domain and its image count changes by one; then leaving the domain is a
// fault only through a face that neither wraps nor is open (a particle beyond
// an open face is removed after the drift; a face is never both).
template <class Real>
struct KickDrift {
  HalfKick<Real> kick;
  Vec3d* position;
  Quaternion* orientation;  // null unless the run's snapshots hold orientations
  ImageCount* image;  // null unless the run is periodic
  const ParticleId* id;
  IntegrationParams p;
  Fault* fault;
  bool closing_kick = false;

  // Inlined into the loop (and into the list's watch, engine/integrator.hpp):
  // as a call per particle it cost the CPU 7 % of its integration.
  GS_HD GS_INLINE void operator()(Index i) const {
    if (kick.is_frozen(i)) return;
    if (closing_kick) kick(i);
    kick(i);
    const Vec3d v = kick.velocity[i];
    const Vec3d step = v * p.dt;
    Vec3d& x = position[i];
    x += step;
    if (image) p.box.wrap(x, image[i]);
    if (p.fp32_state) x = on_fp32_grid(x);
    // Without a kept spin nothing turns: the orientation stays as it started.
    if (orientation && kick.angular_velocity) advance_orientation(orientation[i], kick.angular_velocity[i], p.dt);
    if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && std::isfinite(v.x) &&
          std::isfinite(v.y) && std::isfinite(v.z))) {
      report_fault(fault, kFaultNotFinite, id[i], p.step);
    } else if ((faces_beyond(x, p.domain_lo, p.domain_hi) & ~p.open_faces & ~faces_of_axes(p.box.axes)) != 0) {
      report_fault(fault, kFaultLeftDomain, id[i], p.step);
    } else if (norm2(step) > p.max_displacement * p.max_displacement) {
      report_fault(fault, kFaultTooFast, id[i], p.step);
    }
  }
};

}  // namespace gs
