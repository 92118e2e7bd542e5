#pragma once
// Maps a run's choices (contact model, effects) to the one compiled
// ForceComputer that serves them, for one backend and force precision. Each
// backend includes it once per precision (engine/instances/forces_*_fp32 and
// _fp64), so that the two halves of the instantiations compile in parallel,
// apart from the parts that do not depend on the model.
#include <memory>

#include "contact/contact_models.hpp"
#include "engine/step_kernels.hpp"
#include "engine/force_computer.hpp"

namespace gs {

// The inputs of every force computation of one backend and precision.
template <class Exec, class Real>
struct ForceInputs {
  const std::vector<MaterialSpec>& materials;
  const std::vector<PairSpec>& pairs;
  StepState<Real>& state;
  const NeighbourFinder<Exec>& neighbours;
};

template <class Exec, class Real, class Model, unsigned Effects>
std::unique_ptr<ForceComputation> make_force_computer(const ForceInputs<Exec, Real>& i) {
  return std::make_unique<ForceComputer<Exec, Real, Model, Effects>>(i.materials, i.pairs, i.state, i.neighbours);
}

template <class Exec, class Real, class Model>
std::unique_ptr<ForceComputation> dispatch_effects(unsigned effects, const ForceInputs<Exec, Real>& i) {
  switch (effects & kAllEffects) {
    case 0: return make_force_computer<Exec, Real, Model, 0>(i);
    case 1: return make_force_computer<Exec, Real, Model, 1>(i);
    case 2: return make_force_computer<Exec, Real, Model, 2>(i);
    case 3: return make_force_computer<Exec, Real, Model, 3>(i);
    case 4: return make_force_computer<Exec, Real, Model, 4>(i);
    case 5: return make_force_computer<Exec, Real, Model, 5>(i);
    case 6: return make_force_computer<Exec, Real, Model, 6>(i);
    default: return make_force_computer<Exec, Real, Model, 7>(i);
  }
}

// Every registered contact model with every set of effects, in precision
// Real: instantiated once per backend and precision (engine/instances/forces_*).
template <class Exec, class Real>
std::unique_ptr<ForceComputation> dispatch_forces(const KernelChoice& c, const ContactInputs& in,
                                                  StepState<Real>& state, const NeighbourFinder<Exec>& neighbours) {
  const ForceInputs<Exec, Real> i{in.materials, in.pairs, state, neighbours};
  return with_contact_model(c.model, [&](auto model) { return dispatch_effects<Exec, Real, decltype(model)>(c.effects, i); });
}

}  // namespace gs
