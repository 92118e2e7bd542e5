#define GS_CUDA_HOST_CODE
#include "backend/host_pins.hpp"

#include "backend/check.hpp"

namespace gs {

bool backend_pin_host(Backend b, void* p, std::size_t bytes) {
  if (b == Backend::cpu || bytes == 0) return false;
#ifdef GS_HAVE_CUDA
  const cudaError_t status = cudaHostRegister(p, bytes, cudaHostRegisterDefault);
  if (status == cudaErrorHostMemoryAlreadyRegistered || status == cudaErrorMemoryAllocation) {
    (void)cudaGetLastError();  // clears the error this call left
    return false;
  }
  if (status != cudaSuccess)
    throw_external_error("CUDA", "cudaHostRegister", __FILE__, __LINE__,
                         std::string(cudaGetErrorString(status)) + " (" + std::to_string(bytes) + " bytes)");
  return true;
#else
  (void)p;
  return false;
#endif
}

void backend_unpin_host(Backend b, void* p) noexcept {
  if (b == Backend::cpu || !p) return;
#ifdef GS_HAVE_CUDA
  cudaHostUnregister(p);  // a failure here cannot be acted on: the range is left as it is
#endif
}

void HostPins::pin(Backend b, const void* owner, void* data, std::size_t bytes) {
  auto it = ranges_.find(owner);
  if (it != ranges_.end() && it->second.data == data && it->second.bytes == bytes) return;
  unpin(owner);
  const bool pinned = bytes >= kPinAtLeast && backend_pin_host(b, data, bytes);
  ranges_[owner] = Range{b, data, bytes, pinned};
}

void HostPins::unpin(const void* owner) noexcept {
  auto it = ranges_.find(owner);
  if (it == ranges_.end()) return;
  if (it->second.pinned) backend_unpin_host(it->second.backend, it->second.data);
  ranges_.erase(it);
}

void HostPins::clear() noexcept {
  for (auto& [owner, range] : ranges_)
    if (range.pinned) backend_unpin_host(range.backend, range.data);
  ranges_.clear();
}

std::size_t HostPins::pinned_bytes() const {
  std::size_t total = 0;
  for (const auto& [owner, range] : ranges_)
    if (range.pinned) total += range.bytes;
  return total;
}

}  // namespace gs
