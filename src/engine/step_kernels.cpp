#include "engine/step_kernels.hpp"

#include <stdexcept>

#include "backend/backend.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels(const KernelChoice& c, const ContactInputs& contacts) {
  if (c.backend == Backend::cpu) return make_step_kernels_cpu(c, contacts);
#ifdef GS_HAVE_CUDA
  return make_step_kernels_cuda(c, contacts);
#else
  throw std::runtime_error("backend cuda asked for, but this grainstorm was built without the CUDA backend");
#endif
}

}  // namespace gs
