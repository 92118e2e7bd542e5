#pragma once
// The step's parts for one execution policy `Exec` (CpuExec or CudaExec) and
// force precision `Real`, sharing one StepState. Only the force computation
// depends on the contact model and effects: it is made by dispatch_forces
// (engine/dispatch.hpp), compiled in translation units of its own.
#include <memory>

#include "contact/contact_models.hpp"
#include "engine/integrator.hpp"
#include "engine/neighbour_finder.hpp"
#include "engine/pair_carry.hpp"
#include "engine/particle_mover.hpp"
#include "engine/particle_remover.hpp"
#include "engine/step_kernels.hpp"

namespace gs {

// Marker by side of a plane: front where (x - point) . normal >= 0.
struct MarkByPlane {
  const Vec3d* position;
  std::uint8_t* marker;
  Vec3d point, normal;
  std::uint8_t front, back;
  GS_HD void operator()(Index i) const { marker[i] = dot(position[i] - point, normal) >= 0 ? front : back; }
};

// The force computation of the run's model and effects (engine/dispatch.hpp),
// instantiated in engine/instances/forces_* and only declared here, so that
// the parts below compile apart from the force kernels.
template <class Exec, class Real>
std::unique_ptr<ForceComputation> dispatch_forces(const KernelChoice& c, const ContactInputs& in,
                                                  StepState<Real>& state, const NeighbourFinder<Exec>& neighbours);

template <class Exec, class Real>
class StepKernelsOf final : public StepKernels {
 public:
  StepKernelsOf(const KernelChoice& c, const ContactInputs& in)
      : state_(Exec::backend, history_fields_kept(c.model, c.effects), makes_torques(c.effects), in.contact_slots,
               in.surface_slots),
        finder_(state_.staging), carry_(state_, finder_), mover_(state_, carry_), remover_(mover_),
        integrator_(state_, finder_),
        forces_(dispatch_forces<Exec, Real>(c, in, state_, finder_)) {
    state_.history.row_for_every_particle = in.surface_row_for_every_particle;
  }

  ParticleMovement& movement() override { return mover_; }
  const ParticleMovement& movement() const override { return mover_; }
  NeighbourSearch& neighbours() override { return finder_; }
  ForceComputation& forces() override { return *forces_; }
  const ForceComputation& forces() const override { return *forces_; }
  Integration& integration() override { return integrator_; }
  ParticleRemoval& removal() override { return remover_; }

  void mark_by_plane(ParticleStore& s, const MarkingSpec& m) override {
    Exec::parallel_for(s.n_owned, MarkByPlane{s.position.data(), s.marker.data(), m.point, m.normal, m.front, m.back});
  }
  // The kernels' first fault, or else the neighbour search's (a list kept
  // too long: found a step late, so no kernel could flag it).
  Fault take_fault() override {
    Fault f = state_.fault.to_host()[0];
    if (f.code != kFaultNone) state_.fault.zero();
    const Fault outrun = finder_.take_fault();
    if (outrun.code != kFaultNone && (f.code == kFaultNone || outrun.step < f.step)) return outrun;
    return f;
  }
  void synchronize() const override { Exec::synchronize(); }
  std::size_t bytes() const override {
    return mover_.bytes() + remover_.bytes() + finder_.bytes() + forces_->bytes();
  }

 private:
  StepState<Real> state_;
  NeighbourFinder<Exec> finder_;
  PairCarry<Exec, Real> carry_;  // the pair history across list builds and store changes
  ParticleMover<Exec, Real> mover_;
  ParticleRemover<Exec> remover_;
  Integrator<Exec, Real> integrator_;
  std::unique_ptr<ForceComputation> forces_;
};

// The parts of backend Exec in the force precision of `c`.
template <class Exec>
std::unique_ptr<StepKernels> make_step_kernels_of(const KernelChoice& c, const ContactInputs& in) {
  if (fp32_forces(c.precision)) return std::make_unique<StepKernelsOf<Exec, float>>(c, in);
  return std::make_unique<StepKernelsOf<Exec, double>>(c, in);
}

}  // namespace gs
