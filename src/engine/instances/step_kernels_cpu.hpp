#pragma once
// The CPU's step kernels, one translation unit per force precision.
#include "engine/step_kernels.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cpu_fp32(const KernelChoice& c, const ContactInputs& in);
std::unique_ptr<StepKernels> make_step_kernels_cpu_fp64(const KernelChoice& c, const ContactInputs& in);

}  // namespace gs
