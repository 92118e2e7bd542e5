#define GS_CUDA_HOST_CODE
#include "backend/memory.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

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

#ifdef GS_HAVE_CUDA
// The current device's stream-ordered pool, made to keep what is freed
// (backend/memory.hpp says why) the first time this device allocates.
cudaMemPool_t device_pool() {
  static std::mutex mutex;
  static std::vector<bool> configured;
  int device = 0;
  GS_CUDA_CHECK(cudaGetDevice(&device));
  cudaMemPool_t pool = nullptr;
  GS_CUDA_CHECK(cudaDeviceGetDefaultMemPool(&pool, device));
  std::lock_guard<std::mutex> lock(mutex);
  if (configured.size() <= std::size_t(device)) configured.resize(std::size_t(device) + 1, false);
  if (!configured[std::size_t(device)]) {
    std::uint64_t keep_all = UINT64_MAX;
    GS_CUDA_CHECK(cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReleaseThreshold, &keep_all));
    configured[std::size_t(device)] = true;
  }
  return pool;
}

void* cuda_alloc(std::size_t bytes) {
  void* p = nullptr;
  const bool pooled = cuda_pool_setting();
  const cudaMemPool_t pool = pooled ? device_pool() : nullptr;  // configured before its first allocation
  auto request = [&] { return pooled ? cudaMallocAsync(&p, bytes, cudaStreamLegacy) : cudaMalloc(&p, bytes); };
  cudaError_t status = request();
  if (pooled && status == cudaErrorMemoryAllocation) {
    // Free pages the pool keeps may be what is missing: once the device has
    // finished with everything freed, they go back to the driver and the
    // request is made again, so what fits is what cudaMalloc would fit.
    (void)cudaGetLastError();
    GS_CUDA_CHECK(cudaDeviceSynchronize());
    GS_CUDA_CHECK(cudaMemPoolTrimTo(pool, 0));
    status = request();
  }
  if (status != cudaSuccess)
    throw_external_error("CUDA", pooled ? "cudaMallocAsync" : "cudaMalloc", __FILE__, __LINE__,
                         std::string(cudaGetErrorString(status)) + " (asked for " + std::to_string(bytes) + " bytes)");
  return p;
}
#else
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
    p = cuda_alloc(bytes);
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
    // A failure here cannot be acted on: the context is already broken.
    if (cuda_pool_setting()) cudaFreeAsync(p, cudaStreamLegacy);
    else cudaFree(p);
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
  {
    Usage& u = usage(b);
    std::lock_guard<std::mutex> lock(u.mutex);
    u.peak = u.current;
  }
#ifdef GS_HAVE_CUDA
  if (b == Backend::cuda && cuda_pool_setting()) {
    std::uint64_t from_now = 0;  // resets to what the pool holds now
    GS_CUDA_CHECK(cudaMemPoolSetAttribute(device_pool(), cudaMemPoolAttrReservedMemHigh, &from_now));
  }
#endif
}

std::size_t backend_peak_bytes(Backend b) {
  Usage& u = usage(b);
  std::lock_guard<std::mutex> lock(u.mutex);
  return u.peak;
}

bool parse_cuda_pool_setting(const char* value) {
  const std::string s = value ? value : "";
  if (s.empty() || s == "1") return true;
  if (s == "0") return false;
  throw std::invalid_argument("GRAINSTORM_CUDA_POOL must be 1 or 0, got '" + s + "'");
}

bool cuda_pool_setting() {
  // Read once: memory allocated one way is freed the same way.
  static const bool on = parse_cuda_pool_setting(std::getenv("GRAINSTORM_CUDA_POOL"));
  return on;
}

std::size_t backend_reserved_peak_bytes(Backend b) {
  if (b == Backend::cpu) return backend_peak_bytes(b);
#ifdef GS_HAVE_CUDA
  if (!cuda_pool_setting()) return backend_peak_bytes(b);
  std::uint64_t high = 0;
  GS_CUDA_CHECK(cudaMemPoolGetAttribute(device_pool(), cudaMemPoolAttrReservedMemHigh, &high));
  return std::size_t(high);
#else
  no_cuda();
#endif
}

}  // namespace gs
