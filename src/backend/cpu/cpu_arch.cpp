// Compiled for the x86-64 baseline whatever GS_CPU_ARCH is (src/CMakeLists.txt),
// so that the check below can run on any x86-64 CPU: a binary built for
// x86-64-v3 would otherwise die of SIGILL at its first AVX instruction,
// without a word of why.
#include "backend/cpu/cpu_arch.hpp"

#include <cstdio>
#include <cstdlib>

namespace gs {

const char* host_code_arch() { return GS_CPU_ARCH_NAME; }

}  // namespace gs

#if defined(GS_CPU_ARCH_X86_64_V3)
namespace {

// Before any static constructor of the code compiled for x86-64-v3.
__attribute__((constructor(101))) void refuse_cpu_without_x86_64_v3() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v3")) return;
  std::fputs(
      "grainstorm: this build's host code is for x86-64-v3 (AVX2, FMA), which this CPU lacks; "
      "rebuild with cmake -DGS_CPU_ARCH=x86-64\n",
      stderr);
  std::_Exit(1);
}

}  // namespace
#endif
