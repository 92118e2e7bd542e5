#include "backend/cuda/cuda_exec.cuh"
#include "engine/step_kernels_impl.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cuda(const KernelChoice& c, const ContactInputs& in) {
  return make_step_kernels_of<CudaExec>(c, in);
}

}  // namespace gs
