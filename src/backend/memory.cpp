#define GS_CUDA_HOST_CODE
#include "backend/memory.hpp"

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "backend/check.hpp"

namespace gs {
namespace {

// Bytes in use and the high-water mark, per backend, for the memory report.
struct Usage {
  std::mutex mutex;
  std::unordered_map<void*, std::size_t> sizes;
  std::size_t current = 0, peak = 0;
};
Usage& usage(Backend b) {
  static Usage cpu, cuda;
  return b == Backend::cpu ? cpu : cuda;
}
void record_alloc(Backend b, void* p, std::size_t bytes) {
  Usage& u = usage(b);
  std::lock_guard<std::mutex> lock(u.mutex);
  u.sizes[p] = bytes;
  u.current += bytes;
  if (u.current > u.peak) u.peak = u.current;
}
void record_free(Backend b, void* p) {
  Usage& u = usage(b);
  std::lock_guard<std::mutex> lock(u.mutex);
  auto it = u.sizes.find(p);
  if (it == u.sizes.end()) return;
  u.current -= it->second;
  u.sizes.erase(it);
}

#ifndef GS_HAVE_CUDA
[[noreturn]] void no_cuda() {
  throw std::runtime_error("this grainstorm was built without the CUDA backend (reconfigure with nvcc available)");
}
#endif

}  // namespace

void* backend_alloc(Backend b, std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  void* p = nullptr;
  if (b == Backend::cpu) {
    p = std::aligned_alloc(64, (bytes + 63) / 64 * 64);
    if (!p) throw std::runtime_error("out of host memory allocating " + std::to_string(bytes) + " bytes");
  } else {
#ifdef GS_HAVE_CUDA
    const cudaError_t status = cudaMalloc(&p, bytes);
    if (status != cudaSuccess)
      throw_external_error("CUDA", "cudaMalloc", __FILE__, __LINE__,
                           std::string(cudaGetErrorString(status)) + " (asked for " + std::to_string(bytes) + " bytes)");
#else
    no_cuda();
#endif
  }
  record_alloc(b, p, bytes);
  return p;
}

void backend_free(Backend b, void* p) noexcept {
  if (!p) return;
  record_free(b, p);
  if (b == Backend::cpu) {
    std::free(p);
  } else {
#ifdef GS_HAVE_CUDA
    cudaFree(p);  // a failure here cannot be acted on: the context is already broken
#endif
  }
}

void backend_copy_to_host(Backend b, void* host_dst, const void* src, std::size_t bytes) {
  if (b == Backend::cpu) { std::memcpy(host_dst, src, bytes); return; }
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaMemcpy(host_dst, src, bytes, cudaMemcpyDeviceToHost));
#else
  no_cuda();
#endif
}

void backend_copy_from_host(Backend b, void* dst, const void* host_src, std::size_t bytes) {
  if (b == Backend::cpu) { std::memcpy(dst, host_src, bytes); return; }
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaMemcpy(dst, host_src, bytes, cudaMemcpyHostToDevice));
#else
  no_cuda();
#endif
}

void backend_copy_from_host_queued(Backend b, void* dst, const void* host_src, std::size_t bytes) {
  if (b == Backend::cpu) { std::memcpy(dst, host_src, bytes); return; }
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaMemcpyAsync(dst, host_src, bytes, cudaMemcpyHostToDevice, 0));
#else
  no_cuda();
#endif
}

void backend_copy(Backend b, void* dst, const void* src, std::size_t bytes) {
  if (b == Backend::cpu) { std::memmove(dst, src, bytes); return; }
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToDevice));
#else
  no_cuda();
#endif
}

void backend_zero(Backend b, void* p, std::size_t bytes) {
  if (b == Backend::cpu) { std::memset(p, 0, bytes); return; }
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaMemset(p, 0, bytes));
#else
  no_cuda();
#endif
}

void backend_synchronize(Backend b) {
  if (b == Backend::cpu) return;
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaDeviceSynchronize());
#else
  no_cuda();
#endif
}

void backend_reset_peak(Backend b) {
  Usage& u = usage(b);
  std::lock_guard<std::mutex> lock(u.mutex);
  u.peak = u.current;
}

std::size_t backend_peak_bytes(Backend b) {
  Usage& u = usage(b);
  std::lock_guard<std::mutex> lock(u.mutex);
  return u.peak;
}

}  // namespace gs
