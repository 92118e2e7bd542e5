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
// holds (62 GB for 4e8 spheres). The device instead copies a chunk at a time
// into one half of a fixed-size pinned bounce buffer while host_copy moves
// the chunk before it out of the other half to its place, on every host
// thread (engine/particle_mover_output.hpp).
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
  ~HostPins();
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
  // The bounce buffer as two halves of at least `half_bytes` each, page-locked
  // and kept from call to call, for a pipeline of copies from backend b's
  // memory: while the host reads one half, the device fills the other. False
  // where there is none: on the CPU backend, with pin false, or where the
  // range cannot be pinned (the caller then copies straight into its pageable
  // array, as the driver stages it).
  bool hold_halves(Backend b, std::size_t half_bytes);
  // Queues a copy of `bytes` (at most a half) of the backend's memory at
  // `src` into half h (0 or 1), behind the kernels already launched; more,
  // or no halves held, is a caller's error (std::logic_error).
  void fill_half(int h, const void* src, std::size_t bytes);
  // Half h, once the copy last queued into it is done.
  const unsigned char* filled_half(int h);
  // Waits for the queued copies, unpins the bounce buffer and lets it go.
  void clear() noexcept;
  std::size_t pinned_bytes() const { return bounce_pinned_ ? bounce_.size() : 0; }  // for the tests

 private:
  void wait_half(int h);

  bool pin_ = true;
  std::vector<unsigned char> bounce_;
  std::size_t half_bytes_ = 0;
  Backend bounce_backend_ = Backend::cpu;
  bool bounce_pinned_ = false;
  void* filled_[2] = {};      // per half, the event of the copy last queued into it (cudaEvent_t)
  bool fill_queued_[2] = {};  // whether that copy may still be running
};

}  // namespace gs
