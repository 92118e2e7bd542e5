#pragma once
// Integration over an execution policy and force precision: the half kicks
// read the last forces (and torques, where an effect makes them). The
// kick-drift also checks the Verlet list (ListWatch, fused into the same
// pass over the particles: no kernel of its own), for the list and, with
// ranks, the halo.
#include "engine/integration.hpp"
#include "engine/neighbour_finder.hpp"
#include "engine/step_state.hpp"

namespace gs {

// The kick-drift of particle i, then the list's check of where it went.
template <class Real>
struct KickDriftWatched {
  KickDrift<Real> drift;
  ListWatch watch;

  GS_HD void operator()(Index i) const {
    if (drift.kick.is_frozen(i)) return;
    drift(i);
    watch(i, drift.id[i], drift.position[i], norm(drift.kick.velocity[i]) * drift.p.dt);
  }
};

template <class Exec, class Real>
class Integrator final : public Integration {
 public:
  Integrator(StepState<Real>& state, NeighbourFinder<Exec>& neighbours) : st_(state), neighbours_(neighbours) {}

  void kick_drift(ParticleStore& s, const IntegrationParams& p, bool closing_kick) override {
    ImageCount* image = (s.fields_kept & kImageCounts) != 0 ? s.image.data() : nullptr;
    Quaternion* orientation = (s.fields_kept & kOrientations) != 0 ? s.orientation.data() : nullptr;
    const KickDrift<Real> drift{half_kick(s, p), s.position.data(), orientation, image,
                                s.id.data(),     p,                  st_.fault.data(), closing_kick};
    const ListWatch watch = neighbours_.watch(s, p.step);
    if (!watch.active()) {
      Exec::parallel_for(s.n_owned, drift);
      return;
    }
    Exec::parallel_for(s.n_owned, KickDriftWatched<Real>{drift, watch});
    neighbours_.watch_queued(p.step);
  }
  void kick(ParticleStore& s, const IntegrationParams& p) override { Exec::parallel_for(s.n_owned, half_kick(s, p)); }

 private:
  HalfKick<Real> half_kick(ParticleStore& s, const IntegrationParams& p) {
    Vec3d* spin = (s.fields_kept & kAngularVelocities) != 0 ? s.angular_velocity.data() : nullptr;
    return HalfKick<Real>{s.velocity.data(), spin, st_.forces.force.data(),
                          st_.torque ? st_.forces.torque.data() : nullptr, s.mass.data(), s.inertia.data(),
                          0.5 * p.dt, p.gravity, p.fp32_state,
                          (s.fields_kept & kFrozenFlags) != 0 ? s.frozen.data() : nullptr};
  }

  StepState<Real>& st_;
  NeighbourFinder<Exec>& neighbours_;
};

}  // namespace gs
