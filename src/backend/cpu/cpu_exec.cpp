#include "backend/cpu/cpu_exec.hpp"

#include <omp.h>

#include <utility>
#include <vector>

namespace gs {

namespace {

constexpr int kDigitBits = 11;
constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;

// Thread t's share [begin, end) of n items, in thread order.
Index chunk_begin(Index n, int t, int threads) { return Index(std::int64_t(n) * t / threads); }

}  // namespace

// Least-significant-digit radix sort, 11 bits a pass: stable, O(N) per pass,
// and identical on every machine and for any thread count (equal keys keep
// their order, so the sorted order is one). Each thread counts and scatters its
// own contiguous share of the items; the bucket offsets are laid out bucket
// by bucket, thread by thread, which keeps the scatter stable. Keys already
// in order (the common case between two reorders of a slowly moving bed)
// cost one read; digits in which no two keys differ (the unused high bits of
// ids and cells) are skipped.
template <class Key>
void CpuExec::sort_pairs(SortPairs<Key>& p, void* /*storage*/, std::size_t /*bytes*/) {
  const Index n = p.n;
  Key* keys = p.keys;
  Key* keys_out = p.keys_alt;
  Index* values = p.values;
  Index* values_out = p.values_alt;
  if (n <= 1) return;
  bool in_order = true;
  std::uint64_t varying = 0;
#pragma omp parallel for reduction(&& : in_order) reduction(| : varying) if (n >= kSerialBelow)
  for (Index i = 1; i < n; ++i) {
    in_order = in_order && keys[i - 1] <= keys[i];
    varying |= keys[i] ^ keys[0];
  }
  if (in_order) return;
  std::vector<Index> count;  // [thread][bucket]
  for (int shift = 0; shift < 64 && (varying >> shift) != 0;) {
    while (((varying >> shift) & 1u) == 0) ++shift;  // next bit in which keys differ
#pragma omp parallel if (n >= kSerialBelow)
    {
      const int threads = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
      count.assign(std::size_t(threads) * kBuckets, 0);
      Index* mine = count.data() + std::size_t(t) * kBuckets;
      const Index begin = chunk_begin(n, t, threads), end = chunk_begin(n, t + 1, threads);
      for (Index i = begin; i < end; ++i) ++mine[(keys[i] >> shift) & (kBuckets - 1)];
#pragma omp barrier
#pragma omp single
      {
        Index offset = 0;
        for (std::size_t b = 0; b < kBuckets; ++b)
          for (int u = 0; u < threads; ++u) {
            Index& k = count[std::size_t(u) * kBuckets + b];
            const Index here = k;
            k = offset;
            offset += here;
          }
      }
      for (Index i = begin; i < end; ++i) {
        const Index dst = mine[(keys[i] >> shift) & (kBuckets - 1)]++;
        keys_out[dst] = keys[i];
        values_out[dst] = values[i];
      }
    }
    std::swap(keys, keys_out);
    std::swap(values, values_out);
    shift += kDigitBits;
  }
  // After an odd number of passes the result sits in the alternate buffers.
  p.keys = keys;
  p.values = values;
}

template void CpuExec::sort_pairs<std::uint32_t>(SortPairs<std::uint32_t>&, void*, std::size_t);
template void CpuExec::sort_pairs<std::uint64_t>(SortPairs<std::uint64_t>&, void*, std::size_t);

}  // namespace gs
