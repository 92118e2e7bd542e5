# Instruction set of the host code (GS_CPU_ARCH). The CPU backend's force loop
# is scalar floating-point arithmetic with many square roots and divisions:
# x86-64-v3 (AVX2, FMA: Intel since Haswell, AMD since Excavator and Zen, but
# not every Atom, Celeron or Pentium) runs it about a fifth faster than the
# x86-64 baseline (docs/PERFORMANCE.md). "auto" takes
# x86-64-v3 when the build machine has it, so a build always runs where it
# was built; src/backend/cpu/cpu_arch.cpp refuses, with a message, to start
# on a CPU that lacks the instruction set a binary was built for.
set(GS_CPU_ARCH_IS_X86 OFF)
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  set(GS_CPU_ARCH_IS_X86 ON)
endif()

set(GS_CPU_ARCH_CHOSEN ${GS_CPU_ARCH})
if(GS_CPU_ARCH STREQUAL "auto")
  set(GS_CPU_ARCH_CHOSEN "")
  if(GS_CPU_ARCH_IS_X86)
    include(CheckCXXSourceRuns)
    check_cxx_source_runs([=[
      int main() { __builtin_cpu_init(); return __builtin_cpu_supports("x86-64-v3") ? 0 : 1; }
    ]=] GS_BUILD_MACHINE_HAS_X86_64_V3)
    if(GS_BUILD_MACHINE_HAS_X86_64_V3)
      set(GS_CPU_ARCH_CHOSEN "x86-64-v3")
    else()
      set(GS_CPU_ARCH_CHOSEN "x86-64")
    endif()
  endif()
elseif(NOT GS_CPU_ARCH MATCHES "^(x86-64-v3|native|x86-64)$")
  message(FATAL_ERROR "GS_CPU_ARCH=${GS_CPU_ARCH}: expected auto, x86-64-v3, native or x86-64")
elseif(NOT GS_CPU_ARCH STREQUAL "native" AND NOT GS_CPU_ARCH_IS_X86)
  message(FATAL_ERROR "GS_CPU_ARCH=${GS_CPU_ARCH} names an x86-64 level, but this is ${CMAKE_SYSTEM_PROCESSOR}")
endif()

if(GS_CPU_ARCH_CHOSEN STREQUAL "")
  set(GS_CPU_ARCH_CHOSEN "compiler default")
else()
  add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-march=${GS_CPU_ARCH_CHOSEN}>)
endif()
# Fused multiply-adds only where the source asks for them (mul_add in
# src/core/vec3.hpp): the compiler's own fusing depends on the code inlined
# around an expression, and would make a contact round differently in two
# kernels (CPU ranks with and without neighbours; the rank-independence tests).
add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-ffp-contract=off>)
message(STATUS "grainstorm: host code for ${GS_CPU_ARCH_CHOSEN} (GS_CPU_ARCH=${GS_CPU_ARCH})")
