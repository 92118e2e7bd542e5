#pragma once
// The instruction set the host code was compiled for (GS_CPU_ARCH in CMake).

namespace gs {

// "x86-64-v3", "native", "x86-64" or "compiler default".
const char* host_code_arch();

}  // namespace gs
