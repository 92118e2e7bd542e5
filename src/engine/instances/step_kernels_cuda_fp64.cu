#include "backend/cuda/cuda_exec.cuh"
#include "engine/instances/step_kernels_cuda.hpp"
#include "engine/dispatch.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cuda_fp64(const KernelChoice& c, const ContactInputs& in) {
  return dispatch_step_kernels<CudaExec, double>(c, in);
}

}  // namespace gs
