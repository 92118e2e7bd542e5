#pragma once
// Maps a run's choices (contact model, effects) to the one compiled
// StepKernelsImpl that serves them, for one backend and force precision.
// Each backend includes it once per precision (backend/*/step_kernels_*_fp32
// and _fp64), so that the two halves of the instantiations compile in
// parallel.
#include <memory>

#include "contact/contact_models.hpp"
#include "engine/step_kernels_impl.hpp"

namespace gs {

template <class Exec, class Real, class Model>
std::unique_ptr<StepKernels> dispatch_effects(unsigned effects, const ContactInputs& in) {
  const ContactInputs& i = in;
  switch (effects & kAllEffects) {
    case 0: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 0>>(i.materials, i.pairs, i.contact_slots);
    case 1: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 1>>(i.materials, i.pairs, i.contact_slots);
    case 2: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 2>>(i.materials, i.pairs, i.contact_slots);
    case 3: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 3>>(i.materials, i.pairs, i.contact_slots);
    case 4: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 4>>(i.materials, i.pairs, i.contact_slots);
    case 5: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 5>>(i.materials, i.pairs, i.contact_slots);
    case 6: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 6>>(i.materials, i.pairs, i.contact_slots);
    default: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 7>>(i.materials, i.pairs, i.contact_slots);
  }
}

// Every registered contact model with every set of effects, in precision Real.
template <class Exec, class Real>
std::unique_ptr<StepKernels> dispatch_step_kernels(const KernelChoice& c, const ContactInputs& in) {
  return with_contact_model(c.model, [&](auto model) { return dispatch_effects<Exec, Real, decltype(model)>(c.effects, in); });
}

}  // namespace gs
