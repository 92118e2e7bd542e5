#include "engine/instances/step_kernels_cpu.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cpu(const KernelChoice& c, const ContactInputs& in) {
  return fp32_forces(c.precision) ? make_step_kernels_cpu_fp32(c, in) : make_step_kernels_cpu_fp64(c, in);
}

}  // namespace gs
