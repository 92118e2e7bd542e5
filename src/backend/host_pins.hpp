#pragma once
// Host arrays that a backend copies into again and again (the host copies of
// snapshots and checkpoints), page-locked on the CUDA backend so that the
// device writes them at full speed, with no staging copy through the driver.
// The arrays are plain std::vectors that their owner reuses from one output
// to the next; HostPins resizes them, unpinning a range before the vector
// lets it go, and unpins what is left when it is destroyed (so it must be
// destroyed before the vectors: declare it after them). On the CPU backend
// it only resizes.
#include <cstddef>
#include <unordered_map>
#include <vector>

#include "backend/backend.hpp"

namespace gs {

// Page-locks [p, p + bytes) for copies from the backend's memory (CUDA:
// cudaHostRegister). False, with nothing pinned, where the range cannot be
// (a page it shares is pinned already, or the system's page-locked memory is
// spent): the copies are then merely slower. Other failures throw.
bool backend_pin_host(Backend b, void* p, std::size_t bytes);
void backend_unpin_host(Backend b, void* p) noexcept;

class HostPins {
 public:
  // pin false: only resizes (arrays used once gain nothing from pinning,
  // which costs more than the copy it speeds up).
  explicit HostPins(bool pin = true) : pin_(pin) {}
  ~HostPins() { clear(); }
  HostPins(const HostPins&) = delete;
  HostPins& operator=(const HostPins&) = delete;

  // v.resize(n), v's storage pinned for backend b's copies. Storage that
  // grows is reserved anew and unpinned first, so no pinned range is freed.
  template <class T>
  void resize(Backend b, std::vector<T>& v, std::size_t n) {
    if (n > v.capacity()) {
      unpin(&v);
      v.reserve(n + n / 16);  // room for a few more particles at the next output
    }
    v.resize(n);
    if (pin_ && b != Backend::cpu) pin(b, &v, v.data(), v.capacity() * sizeof(T));
  }
  // Unpins every range (before the vectors it pinned go).
  void clear() noexcept;
  std::size_t pinned_bytes() const;  // for the tests

 private:
  struct Range {
    Backend backend;
    void* data;
    std::size_t bytes;
    bool pinned;
  };
  // Pins `data` for the vector at `owner` unless it is pinned already.
  void pin(Backend b, const void* owner, void* data, std::size_t bytes);
  void unpin(const void* owner) noexcept;

  // Below this a range is left pageable: its copy is short either way, and
  // small vectors share pages with other allocations.
  static constexpr std::size_t kPinAtLeast = std::size_t(1) << 20;
  bool pin_ = true;
  std::unordered_map<const void*, Range> ranges_;  // by the vector's address
};

}  // namespace gs
