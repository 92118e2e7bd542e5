// The force computations of every contact model and set of effects, on the
// CUDA backend in fp32 forces: one translation unit per backend and precision.
#include "backend/cuda/cuda_exec.cuh"
#include "engine/dispatch.hpp"

namespace gs {

template std::unique_ptr<ForceComputation> dispatch_forces<CudaExec, float>(
    const KernelChoice&, const ContactInputs&, StepState<float>&, const NeighbourFinder<CudaExec>&);

}  // namespace gs
