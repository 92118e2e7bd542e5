#include "backend/cpu/cpu_exec.hpp"

#include <utility>
#include <vector>

namespace gs {

// Least-significant-digit radix sort, 11 bits a pass over the bits in use:
// stable, O(N) per pass, and identical on every machine.
void CpuExec::sort_pairs(CellList& c, Index n) {
  constexpr int kDigitBits = 11;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
  std::uint64_t* keys = c.keys.data();
  std::uint64_t* keys_out = c.keys_alt.data();
  Index* values = c.sorted.data();
  Index* values_out = c.sorted_alt.data();
  std::vector<Index> count(kBuckets);
  for (int shift = 0; shift < c.key_bits; shift += kDigitBits) {
    std::fill(count.begin(), count.end(), 0);
    for (Index i = 0; i < n; ++i) ++count[(keys[i] >> shift) & (kBuckets - 1)];
    Index offset = 0;
    for (std::size_t b = 0; b < kBuckets; ++b) {
      const Index k = count[b];
      count[b] = offset;
      offset += k;
    }
    for (Index i = 0; i < n; ++i) {
      const Index dst = count[(keys[i] >> shift) & (kBuckets - 1)]++;
      keys_out[dst] = keys[i];
      values_out[dst] = values[i];
    }
    std::swap(keys, keys_out);
    std::swap(values, values_out);
  }
  // After an odd number of passes the result sits in the alternate buffers.
  if (keys != c.keys.data()) {
    c.keys.swap(c.keys_alt);
    c.sorted.swap(c.sorted_alt);
  }
}

}  // namespace gs
