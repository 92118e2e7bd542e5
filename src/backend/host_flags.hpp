#pragma once
// Flags a kernel raises for the host to read while the kernels queued after
// it run: a ring of two slots (this step's kernel writes one while the host
// reads the other, the last step's), each with the event of the kernel that
// writes it. On CUDA the slots are pinned host memory mapped into the
// device, so the kernel's stores reach the host with no copy, and reading a
// slot waits for its kernel only (cudaEventSynchronize), not for the device;
// on the CPU they are plain memory and nothing waits.
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "backend/backend.hpp"

namespace gs {

class HostFlagRing {
 public:
  static constexpr int kSlots = 2;

  HostFlagRing(Backend b, std::size_t slot_bytes);
  ~HostFlagRing();
  HostFlagRing(const HostFlagRing&) = delete;
  HostFlagRing& operator=(const HostFlagRing&) = delete;

  // Waits for the kernel that last wrote `slot` (queued a step ago or more:
  // done by now), zeroes the slot and returns the address a kernel writes
  // it through.
  void* arm(int slot);
  // The kernel that writes `slot` has been queued (after its launch).
  void queued(int slot);
  // Waits for that kernel and returns the slot as it left it.
  const void* read(int slot);

 private:
  void wait(int slot);

  Backend backend_;
  std::size_t slot_bytes_;
  unsigned char* host_ = nullptr;    // kSlots * slot_bytes_
  unsigned char* device_ = nullptr;  // the same memory as the device addresses it
  void* event_[kSlots] = {};         // cudaEvent_t on CUDA
  bool queued_[kSlots] = {};
};

// The ring over a plain struct of flags T.
template <class T>
class HostFlags {
  static_assert(std::is_trivially_copyable_v<T>, "flags are plain data a kernel writes");

 public:
  explicit HostFlags(Backend b) : ring_(b, sizeof(T)) {}
  T* arm(int slot) { return static_cast<T*>(ring_.arm(slot)); }
  void queued(int slot) { ring_.queued(slot); }
  T read(int slot) {
    T value;
    std::memcpy(&value, ring_.read(slot), sizeof(T));
    return value;
  }

 private:
  HostFlagRing ring_;
};

}  // namespace gs
