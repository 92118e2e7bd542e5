// The force computations of every contact model and set of effects, on the
// CPU backend in fp32 forces: one translation unit per backend and precision.
#include "backend/cpu/cpu_exec.hpp"
#include "engine/dispatch.hpp"

namespace gs {

template std::unique_ptr<ForceComputation> dispatch_forces<CpuExec, float>(
    const KernelChoice&, const ContactInputs&, StepState<float>&, const NeighbourFinder<CpuExec>&);

}  // namespace gs
