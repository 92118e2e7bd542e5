// The force computations of every contact model and set of effects, on the
// CPU backend in fp64 forces: one translation unit per backend and precision.
#include "backend/cpu/cpu_exec.hpp"
#include "engine/dispatch.hpp"

namespace gs {

template std::unique_ptr<ForceComputation> dispatch_forces<CpuExec, double>(
    const KernelChoice&, const ContactInputs&, StepState<double>&, const NeighbourFinder<CpuExec>&);

}  // namespace gs
