#include "backend/cpu/cpu_exec.hpp"
#include "engine/dispatch.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels_cpu(const KernelChoice& c, const PairTableHost& t, int slots) {
  return dispatch_step_kernels<CpuExec>(c, t, slots);
}

}  // namespace gs
