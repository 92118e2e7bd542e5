#include "backend/cpu/cpu_exec.hpp"
#include "engine/step_kernels_impl.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cpu(const KernelChoice& c, const ContactInputs& in) {
  return make_step_kernels_of<CpuExec>(c, in);
}

}  // namespace gs
