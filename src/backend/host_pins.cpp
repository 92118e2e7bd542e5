#define GS_CUDA_HOST_CODE
#include "backend/host_pins.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

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
// A copy's pieces: a share of every host thread, between 64 KiB and kPiece.
// Fixed 1 MiB pieces gave a GPU's output chunk of 3 MB three threads of
// sixteen (docs/PERFORMANCE.md, "Output without an order array").
std::size_t copy_piece(std::size_t bytes) {
  constexpr std::size_t kLeast = std::size_t(64) << 10;
  const std::size_t share = bytes / std::size_t(std::max(1, omp_get_max_threads()));
  return std::clamp(share, kLeast, kPiece);
}
}  // namespace

void host_copy(void* to, const void* from, std::size_t bytes) {
  auto* t = static_cast<unsigned char*>(to);
  const auto* f = static_cast<const unsigned char*>(from);
  const std::size_t piece = copy_piece(bytes);
  const auto pieces = static_cast<std::ptrdiff_t>((bytes + piece - 1) / piece);
#pragma omp parallel for schedule(static) if (pieces > 1)
  for (std::ptrdiff_t k = 0; k < pieces; ++k) {
    const std::size_t at = std::size_t(k) * piece;
    std::memcpy(t + at, f + at, std::min(piece, bytes - at));
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

bool HostPins::hold_halves(Backend b, std::size_t half_bytes) {
  if (!pin_ || b == Backend::cpu) return false;
  if (half_bytes > half_bytes_ || b != bounce_backend_) {
    clear();
    bounce_.resize(2 * half_bytes);
    half_bytes_ = half_bytes;
    bounce_backend_ = b;
    bounce_pinned_ = backend_pin_host(b, bounce_.data(), bounce_.size());
    if (!bounce_pinned_) {  // asked again next time
      std::vector<unsigned char>().swap(bounce_);
      half_bytes_ = 0;
    }
  }
#ifdef GS_HAVE_CUDA
  for (void*& e : filled_) {
    if (e || !bounce_pinned_) continue;
    cudaEvent_t event = nullptr;
    GS_CUDA_CHECK(cudaEventCreateWithFlags(&event, cudaEventDisableTiming));
    e = event;
  }
#endif
  return bounce_pinned_;
}

void HostPins::fill_half(int h, const void* src, std::size_t bytes) {
  if (!bounce_pinned_ || bytes > half_bytes_ || (h != 0 && h != 1))
    throw std::logic_error("HostPins::fill_half: " + std::to_string(bytes) + " bytes into half " + std::to_string(h) +
                           " of " + std::to_string(half_bytes_) + " held");
  wait_half(h);  // the host has read what it held (the caller's order); nothing runs into it
#ifdef GS_HAVE_CUDA
  // The default stream, where every kernel runs (backend/cuda/cuda_exec.cuh).
  GS_CUDA_CHECK(cudaMemcpyAsync(bounce_.data() + std::size_t(h) * half_bytes_, src, bytes, cudaMemcpyDeviceToHost, 0));
  GS_CUDA_CHECK(cudaEventRecord(static_cast<cudaEvent_t>(filled_[h]), 0));
  fill_queued_[h] = true;
#else
  static_cast<void>(src);
  static_cast<void>(bytes);
#endif
}

const unsigned char* HostPins::filled_half(int h) {
  wait_half(h);
  return bounce_.data() + std::size_t(h) * half_bytes_;
}

void HostPins::wait_half(int h) {
  if (!fill_queued_[h]) return;
#ifdef GS_HAVE_CUDA
  GS_CUDA_CHECK(cudaEventSynchronize(static_cast<cudaEvent_t>(filled_[h])));
#endif
  fill_queued_[h] = false;
}

void HostPins::clear() noexcept {
#ifdef GS_HAVE_CUDA
  // A copy may still run into the buffer: wait for it before it is unpinned
  // and freed (a failure here cannot be acted on: the context is broken).
  for (int h = 0; h < 2; ++h)
    if (fill_queued_[h]) cudaEventSynchronize(static_cast<cudaEvent_t>(filled_[h]));
#endif
  fill_queued_[0] = fill_queued_[1] = false;
  if (bounce_pinned_) backend_unpin_host(bounce_backend_, bounce_.data());
  bounce_pinned_ = false;
  half_bytes_ = 0;
  std::vector<unsigned char>().swap(bounce_);
}

HostPins::~HostPins() {
  clear();
#ifdef GS_HAVE_CUDA
  for (void* e : filled_)
    if (e) cudaEventDestroy(static_cast<cudaEvent_t>(e));
#endif
}

}  // namespace gs
