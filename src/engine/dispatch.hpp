#pragma once
// Maps a run's choices (precision, contact model, effects) to the one compiled
// StepKernelsImpl that serves them. Included once per backend.
#include <memory>
#include <stdexcept>

#include "engine/step_kernels_impl.hpp"

namespace gs {

template <class Exec, class Real, ContactModel Model>
std::unique_ptr<StepKernels> dispatch_effects(unsigned effects, const PairTableHost& t, int slots) {
  switch (effects & kAllEffects) {
    case 0: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 0>>(t, slots);
    case 1: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 1>>(t, slots);
    case 2: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 2>>(t, slots);
    case 3: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 3>>(t, slots);
    case 4: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 4>>(t, slots);
    case 5: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 5>>(t, slots);
    case 6: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 6>>(t, slots);
    default: return std::make_unique<StepKernelsImpl<Exec, Real, Model, 7>>(t, slots);
  }
}

template <class Exec, class Real>
std::unique_ptr<StepKernels> dispatch_model(const KernelChoice& c, const PairTableHost& t, int slots) {
  if (c.model == ContactModel::linear) return dispatch_effects<Exec, Real, ContactModel::linear>(c.effects, t, slots);
  return dispatch_effects<Exec, Real, ContactModel::hertz_mindlin>(c.effects, t, slots);
}

template <class Exec>
std::unique_ptr<StepKernels> dispatch_step_kernels(const KernelChoice& c, const PairTableHost& t, int slots) {
  if (fp32_forces(c.precision)) return dispatch_model<Exec, float>(c, t, slots);
  return dispatch_model<Exec, double>(c, t, slots);
}

}  // namespace gs
