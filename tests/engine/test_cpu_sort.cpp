// The CPU backend's radix sort of (cell, id) keys against std::sort, for
// sizes below and above the threshold where threads join in, keys already in
// order, and keys that differ in only a few bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "backend/cpu/cpu_exec.hpp"

namespace gs {
namespace {

template <class Key>
void expect_sorted_like_std(const std::vector<Key>& keys) {
  const Index n = Index(keys.size());
  std::vector<Key> key_buffer = keys, key_alt(keys.size());
  std::vector<Index> order(keys.size()), value_buffer(keys.size()), value_alt(keys.size());
  std::iota(order.begin(), order.end(), 0);
  value_buffer = order;
  SortPairs<Key> p{key_buffer.data(), key_alt.data(), value_buffer.data(), value_alt.data(), n, 8 * int(sizeof(Key))};
  CpuExec::sort_pairs(p, nullptr, 0);
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return keys[std::size_t(a)] < keys[std::size_t(b)]; });
  std::vector<Key> want(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) want[i] = keys[std::size_t(order[i])];
  EXPECT_EQ(std::vector<Key>(p.keys, p.keys + n), want) << "n = " << n;
  EXPECT_EQ(std::vector<Index>(p.values, p.values + n), order) << "n = " << n;
}

// Unique keys as the cell list builds them: cell << 32 | id.
std::vector<std::uint64_t> cell_keys(std::size_t n, std::uint64_t cells, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint64_t> k(n);
  for (std::size_t i = 0; i < n; ++i) k[i] = ((rng() % cells) << 32) | std::uint64_t(i);
  std::shuffle(k.begin(), k.end(), rng);
  return k;
}

TEST(CpuSort, MatchesStdSort) {
  for (std::size_t n : {0, 1, 2, 100, 4095, 4096, 5000, 200003}) expect_sorted_like_std(cell_keys(n, 70000, 7));
  // Keys that differ in the id only, and in the top cell bits only.
  expect_sorted_like_std(cell_keys(50000, 1, 8));
  std::vector<std::uint64_t> top = cell_keys(50000, 4, 9);
  for (auto& k : top) k = (k & 0xFFFFFFFF00000000ull) << 29 | (k & 0xFFFFFFFFull);
  expect_sorted_like_std(top);
  // Already in order: nothing moves.
  std::vector<std::uint64_t> sorted = cell_keys(30000, 1000, 10);
  std::sort(sorted.begin(), sorted.end());
  expect_sorted_like_std(sorted);
}

// 32-bit keys (a cell alone, or an id), with repeats: the sort is stable, so
// equal keys keep their order (the values say so: std::sort's comparison
// falls back on them).
TEST(CpuSort, ThirtyTwoBitKeysStable) {
  std::mt19937 rng(11);
  for (std::size_t n : {0, 1, 3, 4096, 70001}) {
    std::vector<std::uint32_t> keys(n);
    for (auto& k : keys) k = std::uint32_t(rng() % 5000) << (n % 2 == 0 ? 20 : 0);
    const Index m = Index(n);
    std::vector<std::uint32_t> key_buffer = keys, key_alt(n);
    std::vector<Index> values(n), value_alt(n), order(n);
    std::iota(values.begin(), values.end(), 0);
    std::iota(order.begin(), order.end(), 0);
    SortPairs<std::uint32_t> p{key_buffer.data(), key_alt.data(), values.data(), value_alt.data(), m, 32};
    CpuExec::sort_pairs(p, nullptr, 0);
    std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return keys[std::size_t(a)] < keys[std::size_t(b)]; });
    EXPECT_EQ(std::vector<Index>(p.values, p.values + m), order) << "n = " << n;
  }
}

}  // namespace
}  // namespace gs
