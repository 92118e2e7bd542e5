#pragma once
// Bisection over indices, in host and device code.
#include "core/hd.hpp"

namespace gs {

// The first index k in [lo, hi) at which below(k) is false, or hi, where
// below is true on a prefix of the range and false after it (as
// std::partition_point over indices): in a range sorted ascending, with
// below(k) = a[k] < key, the first entry not below key.
template <class I, class Below>
GS_HD GS_INLINE I partition_point(I lo, I hi, const Below& below) {
  while (lo < hi) {
    const I mid = lo + (hi - lo) / 2;
    if (below(mid)) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

}  // namespace gs
