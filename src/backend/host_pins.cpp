#define GS_CUDA_HOST_CODE
#include "backend/host_pins.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

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

namespace {
// Pieces of a parallel copy or touch: large enough that a thread's share
// streams, small enough that every thread has a few.
constexpr std::size_t kPiece = std::size_t(1) << 20;
}  // namespace

void host_copy(void* to, const void* from, std::size_t bytes) {
  auto* t = static_cast<unsigned char*>(to);
  const auto* f = static_cast<const unsigned char*>(from);
  const auto pieces = static_cast<std::ptrdiff_t>((bytes + kPiece - 1) / kPiece);
#pragma omp parallel for schedule(static) if (pieces > 1)
  for (std::ptrdiff_t k = 0; k < pieces; ++k) {
    const std::size_t at = std::size_t(k) * kPiece;
    std::memcpy(t + at, f + at, std::min(kPiece, bytes - at));
  }
}

void touch_pages(void* p, std::size_t bytes) {
  if (bytes == 0) return;
  static const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
  const auto first = reinterpret_cast<std::uintptr_t>(p), end = first + bytes;
  const std::uintptr_t first_page = first / page, pages = (end - 1) / page - first_page + 1;
  const auto count = static_cast<std::ptrdiff_t>(pages);
#pragma omp parallel for schedule(static) if (bytes >= 4 * kPiece)
  for (std::ptrdiff_t k = 0; k < count; ++k) {  // the page's first byte in the range
    const std::uintptr_t at = std::max(first, (first_page + std::uintptr_t(k)) * page);
    *reinterpret_cast<volatile unsigned char*>(at) = 0;
  }
}

unsigned char* HostPins::bounce(Backend b, std::size_t bytes) {
  if (!pin_ || b == Backend::cpu) return nullptr;
  if (bytes > bounce_.size() || b != bounce_backend_) {
    clear();
    bounce_.resize(bytes);
    bounce_backend_ = b;
    bounce_pinned_ = backend_pin_host(b, bounce_.data(), bounce_.size());
    if (!bounce_pinned_) std::vector<unsigned char>().swap(bounce_);  // asked again next time
  }
  return bounce_pinned_ ? bounce_.data() : nullptr;
}

void HostPins::clear() noexcept {
  if (bounce_pinned_) backend_unpin_host(bounce_backend_, bounce_.data());
  bounce_pinned_ = false;
  std::vector<unsigned char>().swap(bounce_);
}

}  // namespace gs
