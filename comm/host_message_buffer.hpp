#pragma once
// A host buffer for messages of a size that changes little from step to step
// (the halo's forward between rebuilds): kept from one message to the next,
// since a fresh buffer every step had its pages faulted in and zeroed by the
// kernel every step, and, on a GPU backend, page-locked, so that the device's
// copies into and out of it run at the bus's speed without the driver
// staging them through a buffer of its own.
#include <cstddef>
#include <memory>
#include <utility>

#include "backend/backend.hpp"
#include "backend/host_pins.hpp"

namespace gs {

class HostMessageBuffer {
 public:
  HostMessageBuffer() = default;
  ~HostMessageBuffer() { release(); }
  HostMessageBuffer(const HostMessageBuffer&) = delete;
  HostMessageBuffer& operator=(const HostMessageBuffer&) = delete;
  HostMessageBuffer(HostMessageBuffer&& o) noexcept { swap(o); }
  HostMessageBuffer& operator=(HostMessageBuffer&& o) noexcept {
    HostMessageBuffer(std::move(o)).swap(*this);
    return *this;
  }

  // At least `bytes` of storage for copies to and from backend b's memory;
  // what it held is not kept. It grows with room for a few percent more
  // (ghosts come and go between rebuilds of the halo) and never shrinks.
  unsigned char* hold(Backend b, std::size_t bytes) {
    if (bytes > capacity_ || b != backend_) {
      release();
      const std::size_t capacity = bytes + bytes / 16;
      data_.reset(new unsigned char[capacity]);  // not zeroed here: on every host thread, below
      touch_pages(data_.get(), capacity);
      capacity_ = capacity;
      backend_ = b;
      pinned_ = backend_pin_host(b, data_.get(), capacity);
    }
    return data_.get();
  }
  unsigned char* data() { return data_.get(); }
  bool pinned() const { return pinned_; }

 private:
  void release() noexcept {
    if (pinned_) backend_unpin_host(backend_, data_.get());
    pinned_ = false;
    data_.reset();
    capacity_ = 0;
  }
  void swap(HostMessageBuffer& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(capacity_, o.capacity_);
    std::swap(backend_, o.backend_);
    std::swap(pinned_, o.pinned_);
  }

  std::unique_ptr<unsigned char[]> data_;
  std::size_t capacity_ = 0;
  Backend backend_ = Backend::cpu;
  bool pinned_ = false;
};

}  // namespace gs
