#pragma once
// Layout of the contact history: entry (slot s, particle i) lives at
// s * slot_stride + i * particle_stride. The execution policy picks the order:
// slot-major on the GPU, so that neighbouring threads touch neighbouring words;
// particle-major on the CPU, so that one thread's slots share a cache line.
#include <cstddef>

#include "core/hd.hpp"
#include "core/types.hpp"

namespace gs {

// The row of a particle without one in a table of surface slots
// (contact/contact_slots.hpp).
constexpr Index kNoSurfaceRow = -1;

enum class HistoryOrder { slot_major, particle_major };

struct HistoryStrides {
  std::size_t slot_stride = 0;
  std::size_t particle_stride = 0;

  // Strides of a history of `slots` slots for `capacity` particles.
  static HistoryStrides of(HistoryOrder order, int slots, std::size_t capacity) {
    if (order == HistoryOrder::slot_major) return {capacity, 1};
    return {1, std::size_t(slots)};
  }
  GS_HD std::size_t at(int s, std::size_t i) const { return std::size_t(s) * slot_stride + i * particle_stride; }
};

}  // namespace gs
