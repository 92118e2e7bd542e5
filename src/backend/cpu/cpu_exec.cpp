#include "backend/cpu/cpu_exec.hpp"

#include <utility>
#include <vector>

namespace gs {

// Least-significant-digit radix sort, 11 bits a pass: stable, O(N) per pass,
// and identical on every machine. Keys already in order (the common case
// between two reorders of a slowly moving bed) cost one read; digits in which
// no two keys differ (the unused high bits of ids and cells) are skipped.
void CpuExec::sort_pairs(CellList& c, Index n) {
  constexpr int kDigitBits = 11;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
  std::uint64_t* keys = c.keys.data();
  std::uint64_t* keys_out = c.keys_alt.data();
  Index* values = c.sorted.data();
  Index* values_out = c.sorted_alt.data();
  if (n <= 1) return;
  bool in_order = true;
  std::uint64_t varying = 0;
  for (Index i = 1; i < n; ++i) {
    in_order = in_order && keys[i - 1] <= keys[i];
    varying |= keys[i] ^ keys[0];
  }
  if (in_order) return;
  std::vector<Index> count(kBuckets);
  for (int shift = 0; shift < 64 && (varying >> shift) != 0;) {
    while (((varying >> shift) & 1u) == 0) ++shift;  // next bit in which keys differ
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
    shift += kDigitBits;
  }
  // After an odd number of passes the result sits in the alternate buffers.
  if (keys != c.keys.data()) {
    c.keys.swap(c.keys_alt);
    c.sorted.swap(c.sorted_alt);
  }
}

}  // namespace gs
