#pragma once
// Integration over an execution policy and force precision: the half kicks
// read the last forces (and torques, where an effect makes them).
#include "engine/integration.hpp"
#include "engine/step_state.hpp"

namespace gs {

template <class Exec, class Real>
class Integrator final : public Integration {
 public:
  explicit Integrator(StepState<Real>& state) : st_(state) {}

  void kick_drift(ParticleStore& s, const IntegrationParams& p) override {
    ImageCount* image = (s.fields_kept & kImageCounts) != 0 ? s.image.data() : nullptr;
    Exec::parallel_for(s.n_owned, KickDrift<Real>{half_kick(s, p), s.position.data(), s.orientation.data(), image,
                                                  s.id.data(), p, st_.fault.data()});
  }
  void kick(ParticleStore& s, const IntegrationParams& p) override { Exec::parallel_for(s.n_owned, half_kick(s, p)); }

 private:
  HalfKick<Real> half_kick(ParticleStore& s, const IntegrationParams& p) {
    return HalfKick<Real>{s.velocity.data(), s.angular_velocity.data(), st_.forces.force.data(),
                          st_.torque ? st_.forces.torque.data() : nullptr, s.mass.data(), s.inertia.data(),
                          0.5 * p.dt, p.gravity, p.fp32_state,
                          (s.fields_kept & kFrozenFlags) != 0 ? s.frozen.data() : nullptr};
  }

  StepState<Real>& st_;
};

}  // namespace gs
