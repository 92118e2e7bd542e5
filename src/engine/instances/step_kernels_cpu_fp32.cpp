#include "backend/cpu/cpu_exec.hpp"
#include "engine/instances/step_kernels_cpu.hpp"
#include "engine/dispatch.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cpu_fp32(const KernelChoice& c, const ContactInputs& in) {
  return dispatch_step_kernels<CpuExec, float>(c, in);
}

}  // namespace gs
