// The force computations of every contact model and set of effects, on the
// CUDA backend in fp64 forces: one translation unit per backend and precision.
#include "backend/cuda/cuda_exec.cuh"
#include "engine/dispatch.hpp"

namespace gs {

template std::unique_ptr<ForceComputation> dispatch_forces<CudaExec, double>(
    const KernelChoice&, const ContactInputs&, StepState<double>&, const NeighbourFinder<CudaExec>&);

}  // namespace gs
