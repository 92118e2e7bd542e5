#pragma once
// Sums over the particles of a snapshot on every host thread that come out
// the same bits whatever the threads: each block of kSumBlock particles is
// summed in index order by one thread, and the blocks' sums are added in
// block order. A snapshot gathered in id order gives the same bits whatever
// the ranks too. (One thread over 64e6 particles held each snapshot of a GPU
// run for seconds: docs/PERFORMANCE.md, "The output's split".)
#include <algorithm>
#include <cstddef>
#include <vector>

namespace gs {

constexpr std::size_t kSumBlock = 4096;

// add_particle(T& block_sum, i) adds particle i; add_block(T& total, const T&
// block_sum) adds a block's sum; both start from `zero`.
template <class T, class AddParticle, class AddBlock>
T sum_in_blocks(std::size_t n, const T& zero, const AddParticle& add_particle, const AddBlock& add_block) {
  const std::size_t blocks = (n + kSumBlock - 1) / kSumBlock;
  std::vector<T> partial(blocks, zero);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::ptrdiff_t b = 0; b < std::ptrdiff_t(blocks); ++b) {
    const std::size_t end = std::min(n, (std::size_t(b) + 1) * kSumBlock);
    for (std::size_t i = std::size_t(b) * kSumBlock; i < end; ++i) add_particle(partial[std::size_t(b)], i);
  }
  T total = zero;
  for (const T& p : partial) add_block(total, p);
  return total;
}

}  // namespace gs
