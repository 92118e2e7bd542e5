#pragma once
// Bit counts of 32-bit masks, in host and device code.
#include "core/hd.hpp"

namespace gs {

// How many bits of v are set.
GS_HD GS_INLINE int bit_count(unsigned v) {
#if defined(__CUDA_ARCH__)
  return __popc(v);
#else
  return __builtin_popcount(v);
#endif
}

// The index of v's lowest set bit; v != 0.
GS_HD GS_INLINE int lowest_bit(unsigned v) {
#if defined(__CUDA_ARCH__)
  return __ffs(int(v)) - 1;
#else
  return __builtin_ctz(v);
#endif
}

}  // namespace gs
