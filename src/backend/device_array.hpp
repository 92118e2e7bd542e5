#pragma once
#include <cassert>
#include <cstddef>
#include <utility>
#include <vector>

#include "backend/memory.hpp"

namespace gs {

// An array in a backend's memory. Owns its storage; moves, never copies.
// Capacity only grows (until discard()), so buffers reused every step are
// allocated once.
template <class T>
class DeviceArray {
 public:
  using value_type = T;
  DeviceArray() = default;
  explicit DeviceArray(Backend b, std::size_t n = 0) : backend_(b) { resize(n); }
  ~DeviceArray() { release(); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& o) noexcept { swap(o); }
  DeviceArray& operator=(DeviceArray&& o) noexcept { swap(o); return *this; }

  void swap(DeviceArray& o) noexcept {
    std::swap(backend_, o.backend_);
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }

  // Grows keeping the first size() elements.
  void resize(std::size_t n) {
    if (n > capacity_) {
      std::size_t new_capacity = capacity_ + capacity_ / 4;
      if (new_capacity < n) new_capacity = n;
      grow_to(new_capacity);
    }
    size_ = n;
  }
  // Room for n elements, keeping the first size(): a resize up to n then
  // allocates nothing (no old and new storage held at once as it grows).
  void reserve(std::size_t n) {
    if (n > capacity_) grow_to(n);
  }
  // For scratch whose contents need not survive: grows without copying, so
  // the old and the new storage are never held at once (no peak of both).
  void resize_discarding(std::size_t n) {
    if (n > capacity_) {
      release();
      size_ = 0;
    }
    resize(n);
  }
  // Frees the storage (no elements, no capacity): for arrays a phase of a
  // step rewrites whole, so that what another phase holds never stands
  // beside them at the peak. On a GPU the device's pool keeps the pages for
  // the next allocation (backend/memory.hpp): no wait for the device.
  void discard() noexcept {
    release();
    size_ = 0;
  }
  void zero() { if (size_ > 0) backend_zero(backend_, data_, size_ * sizeof(T)); }

  std::vector<T> to_host() const {
    std::vector<T> h(size_);
    if (size_ > 0) backend_copy_to_host(backend_, h.data(), data_, size_ * sizeof(T));
    return h;
  }
  void from_host(const std::vector<T>& h) {
    resize(h.size());
    if (!h.empty()) backend_copy_from_host(backend_, data_, h.data(), h.size() * sizeof(T));
  }

  // The same, queued behind the kernels already launched (no wait for them):
  // for small arrays a step changes, such as the walls' poses.
  void from_host_queued(const std::vector<T>& h) {
    resize(h.size());
    if (!h.empty()) backend_copy_from_host_queued(backend_, data_, h.data(), h.size() * sizeof(T));
  }

  // Copies `count` host values into [at, at + count), which must lie within size().
  void from_host(const T* h, std::size_t count, std::size_t at) {
    assert(at + count <= size_);
    if (count > 0) backend_copy_from_host(backend_, data_ + at, h, count * sizeof(T));
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t bytes() const { return capacity_ * sizeof(T); }
  Backend backend() const { return backend_; }

 private:
  void grow_to(std::size_t capacity) {
    T* fresh = static_cast<T*>(backend_alloc(backend_, capacity * sizeof(T)));
    if (size_ > 0) backend_copy(backend_, fresh, data_, size_ * sizeof(T));
    release();
    data_ = fresh;
    capacity_ = capacity;
  }
  void release() noexcept {
    if (data_) backend_free(backend_, data_);
    data_ = nullptr;
    capacity_ = 0;
  }
  Backend backend_ = Backend::cpu;
  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

}  // namespace gs
