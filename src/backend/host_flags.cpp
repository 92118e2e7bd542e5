#define GS_CUDA_HOST_CODE
#include "backend/host_flags.hpp"

#include <cstdlib>
#include <new>
#include <stdexcept>

#include "backend/check.hpp"

namespace gs {

HostFlagRing::HostFlagRing(Backend b, std::size_t slot_bytes) : backend_(b), slot_bytes_(slot_bytes) {
  const std::size_t bytes = kSlots * slot_bytes_;
  if (b == Backend::cpu) {
    host_ = static_cast<unsigned char*>(std::calloc(1, bytes));
    if (!host_) throw std::bad_alloc();
    device_ = host_;
    return;
  }
#ifdef GS_HAVE_CUDA
  void* p = nullptr;
  GS_CUDA_CHECK(cudaHostAlloc(&p, bytes, cudaHostAllocMapped));
  host_ = static_cast<unsigned char*>(p);
  std::memset(host_, 0, bytes);
  void* d = nullptr;
  GS_CUDA_CHECK(cudaHostGetDevicePointer(&d, p, 0));
  device_ = static_cast<unsigned char*>(d);
  for (void*& e : event_) {
    cudaEvent_t event = nullptr;
    GS_CUDA_CHECK(cudaEventCreateWithFlags(&event, cudaEventDisableTiming));
    e = event;
  }
#else
  throw std::runtime_error("this grainstorm was built without the CUDA backend (reconfigure with nvcc available)");
#endif
}

HostFlagRing::~HostFlagRing() {
  if (backend_ == Backend::cpu) {
    std::free(host_);
    return;
  }
#ifdef GS_HAVE_CUDA
  // Failures here cannot be acted on: the context is already broken.
  for (void* e : event_)
    if (e) cudaEventDestroy(static_cast<cudaEvent_t>(e));
  if (host_) cudaFreeHost(host_);
#endif
}

void HostFlagRing::wait(int slot) {
  if (!queued_[slot]) return;
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaEventSynchronize(static_cast<cudaEvent_t>(event_[slot])));
#endif
  queued_[slot] = false;
}

void* HostFlagRing::arm(int slot) {
  wait(slot);
  std::memset(host_ + std::size_t(slot) * slot_bytes_, 0, slot_bytes_);
  return device_ + std::size_t(slot) * slot_bytes_;
}

void HostFlagRing::queued(int slot) {
  if (backend_ == Backend::cpu) return;
#ifdef GS_HAVE_CUDA
  // The default stream, which the kernels run on (backend/cuda/cuda_exec.cuh).
  GS_CUDA_CHECK(cudaEventRecord(static_cast<cudaEvent_t>(event_[slot]), 0));
  queued_[slot] = true;
#else
  static_cast<void>(slot);
#endif
}

const void* HostFlagRing::read(int slot) {
  wait(slot);
  return host_ + std::size_t(slot) * slot_bytes_;
}

}  // namespace gs
