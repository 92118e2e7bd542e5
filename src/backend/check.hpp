#pragma once
// One way to check every external call: a failed CUDA, MPI, NCCL or HDF5 call
// throws gs::ExternalError naming the call site, the rank and the library's
// own message. The caller decides whether to stop all ranks.
#include <stdexcept>
#include <string>

namespace gs {

struct ExternalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The rank of this process for messages (0 when not under MPI).
int& current_rank();

[[noreturn]] void throw_external_error(const char* library, const char* call, const char* file, int line,
                                       const std::string& message);

}  // namespace gs

#if defined(GS_HAVE_CUDA) && (defined(__CUDACC__) || defined(GS_CUDA_HOST_CODE))
#include <cuda_runtime.h>
#define GS_CUDA_CHECK(call)                                                                  \
  do {                                                                                       \
    cudaError_t gs_status_ = (call);                                                         \
    if (gs_status_ != cudaSuccess)                                                           \
      ::gs::throw_external_error("CUDA", #call, __FILE__, __LINE__, cudaGetErrorString(gs_status_)); \
  } while (0)
#endif
