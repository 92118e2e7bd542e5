#pragma once
// Host arrays that a backend copies into again and again (the host copies of
// snapshots and checkpoints), and the one page-locked buffer those copies
// pass through on the CUDA backend. The arrays are plain std::vectors that
// their owner reuses from one output to the next: HostPins resizes them, and
// faults in the pages of storage that grows on every host thread (the
// kernel's zeroing of fresh pages, otherwise done one page at a time by the
// thread that first writes them, was most of a first output's time). They
// stay pageable: page-locking whole arrays (cudaHostRegister) took longer
// than the copies it sped up, and locked as much host memory as a snapshot
// holds (62 GB for 4e8 spheres). The device instead writes a fixed-size
// pinned bounce buffer, a chunk at a time, and host_copy moves each chunk
// to its place on every host thread (engine/particle_mover_output.hpp).
#include <cstddef>
#include <type_traits>
#include <vector>

#include "backend/backend.hpp"

namespace gs {

// Page-locks [p, p + bytes) for copies from the backend's memory (CUDA:
// cudaHostRegister). False, with nothing pinned, where the range cannot be
// (a page it shares is pinned already, or the system's page-locked memory is
// spent): the copies are then merely slower. Other failures throw.
bool backend_pin_host(Backend b, void* p, std::size_t bytes);
void backend_unpin_host(Backend b, void* p) noexcept;

// memcpy of host memory on every host thread (OpenMP), for large copies.
void host_copy(void* to, const void* from, std::size_t bytes);
// Writes a zero to a byte of every page [p, p + bytes) reaches into, on
// every host thread: the pages of fresh memory are faulted in (and zeroed by
// the kernel) in parallel. The range's other bytes are left as they are.
void touch_pages(void* p, std::size_t bytes);

class HostPins {
 public:
  // pin false: no bounce buffer (a copy made once gains nothing from
  // pinning, which costs more than the copy it speeds up).
  explicit HostPins(bool pin = true) : pin_(pin) {}
  ~HostPins() { clear(); }
  HostPins(const HostPins&) = delete;
  HostPins& operator=(const HostPins&) = delete;

  // v.resize(n). Storage that grows is reserved anew with a little room, and
  // its pages past the kept values faulted in on every host thread before the
  // resize writes them.
  template <class T>
  void resize(Backend, std::vector<T>& v, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>, "host arrays of plain values");
    if (n > v.capacity()) {
      v.reserve(n + n / 16);  // room for a few more particles at the next output
      touch_pages(v.data() + v.size(), (v.capacity() - v.size()) * sizeof(T));
    }
    v.resize(n);
  }
  // A page-locked host buffer of at least `bytes` for backend b's copies,
  // kept from call to call; null where there is none: on the CPU backend,
  // with pin false, or where the range cannot be pinned (the caller then
  // copies straight into its pageable array, as the driver stages it).
  unsigned char* bounce(Backend b, std::size_t bytes);
  // Unpins the bounce buffer and lets it go.
  void clear() noexcept;
  std::size_t pinned_bytes() const { return bounce_pinned_ ? bounce_.size() : 0; }  // for the tests

 private:
  bool pin_ = true;
  std::vector<unsigned char> bounce_;
  Backend bounce_backend_ = Backend::cpu;
  bool bounce_pinned_ = false;
};

}  // namespace gs
