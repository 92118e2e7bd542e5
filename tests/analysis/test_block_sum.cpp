// Sums in fixed blocks (analysis/block_sum.hpp): the same bits on one host
// thread and on three, and those of the blocks summed one after another by
// hand; a sum that followed the threads (a reduction) would round otherwise.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "analysis/block_sum.hpp"

namespace gs {
namespace {

TEST(BlockSum, SameBitsWhateverTheThreadsAndThoseOfTheBlocksInOrder) {
  // Values over many orders of magnitude and both signs, so that any other
  // order of the additions rounds differently.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> exponent(-8, 8), sign(-1, 1);
  std::vector<double> x(200003);
  for (double& v : x) v = (sign(rng) < 0 ? -1 : 1) * std::pow(10.0, exponent(rng));
  auto sum = [&] {
    return sum_in_blocks(
        x.size(), 0.0, [&](double& a, std::size_t i) { a += x[i]; }, [](double& t, const double& b) { t += b; });
  };
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const double one = sum();
  omp_set_num_threads(3);
  const double three = sum();
  omp_set_num_threads(threads);
  double by_hand = 0;
  for (std::size_t first = 0; first < x.size(); first += kSumBlock) {
    double block = 0;
    for (std::size_t i = first; i < std::min(x.size(), first + kSumBlock); ++i) block += x[i];
    by_hand += block;
  }
  EXPECT_EQ(one, by_hand);
  EXPECT_EQ(three, by_hand);
  double in_order = 0;
  for (double v : x) in_order += v;
  EXPECT_NE(in_order, by_hand) << "the values should round differently in another order";
}

}  // namespace
}  // namespace gs
