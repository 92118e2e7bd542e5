#include "backend/cuda/cuda_exec.cuh"
#include "engine/dispatch.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cuda(const KernelChoice& c, const PairTableHost& t, int slots) {
  return dispatch_step_kernels<CudaExec>(c, t, slots);
}

}  // namespace gs
