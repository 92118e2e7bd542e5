// Particles in id order in linear time (core/id_order.hpp), against a
// comparison sort of the same ids: dense ids in any order, ids with the gaps
// removals leave, sparse ids (the radix path) and repeated ids (kept in order
// of appearance, as a stable sort keeps them).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "core/id_order.hpp"

namespace gs {
namespace {

std::vector<std::size_t> stable_sorted(const std::vector<ParticleId>& id) {
  std::vector<std::size_t> order(id.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  return order;
}

std::vector<ParticleId> shuffled(std::vector<ParticleId> id, unsigned seed) {
  std::mt19937 random(seed);
  std::shuffle(id.begin(), id.end(), random);
  return id;
}

TEST(IdOrder, DenseIdsInAnyOrder) {
  std::vector<ParticleId> id(200000);
  std::iota(id.begin(), id.end(), ParticleId(0));
  id = shuffled(id, 1);
  EXPECT_EQ(id_order(id), stable_sorted(id));
}

TEST(IdOrder, IdsWithGapsFromRemovals) {
  std::vector<ParticleId> id;
  for (ParticleId k = 1000; k < 400000; ++k)
    if (k % 3 != 0 || k % 7 == 0) id.push_back(k);  // about 2/3 of the range is left
  id = shuffled(id, 2);
  EXPECT_EQ(id_order(id), stable_sorted(id));
}

TEST(IdOrder, SparseIds) {
  std::mt19937 random(3);
  std::vector<ParticleId> id(50000);
  for (ParticleId& x : id) x = ParticleId(random());  // across the whole 32-bit range
  id.push_back(0xFFFFFFFEu);
  id.push_back(0);
  EXPECT_EQ(id_order(id), stable_sorted(id));
}

TEST(IdOrder, RepeatedIdsKeepTheirOrder) {
  const std::vector<ParticleId> dense = {5, 3, 5, 4, 3, 6, 5};
  EXPECT_EQ(id_order(dense), stable_sorted(dense));
  std::vector<ParticleId> sparse = {4000000000u, 7, 4000000000u, 12, 7};
  EXPECT_EQ(id_order(sparse), stable_sorted(sparse));
}

TEST(IdOrder, PermutedFollowsTheOrder) {
  const std::vector<ParticleId> id = {30, 10, 20};
  const std::vector<double> mass = {3.0, 1.0, 2.0};
  EXPECT_EQ(permuted(mass, id_order(id)), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_TRUE(id_order({}).empty());
}

}  // namespace
}  // namespace gs
