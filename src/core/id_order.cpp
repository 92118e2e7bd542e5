#include "core/id_order.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace gs {
namespace {

constexpr std::uint32_t kNoRow = std::numeric_limits<std::uint32_t>::max();

// Dense ids (range at most a few times the count): each id marks its slot,
// the marked slots read in order are the sorted order. Empty when two ids
// share a slot (the caller then sorts stably).
std::vector<std::size_t> scattered_by_id(const std::vector<ParticleId>& id, ParticleId lowest, std::size_t range) {
  std::vector<std::uint32_t> row_of(range, kNoRow);
  const auto n = static_cast<std::ptrdiff_t>(id.size());
#pragma omp parallel for schedule(static) if (n > 100000)
  for (std::ptrdiff_t i = 0; i < n; ++i)  // atomic: two equal ids may race for a slot
    __atomic_store_n(&row_of[id[std::size_t(i)] - lowest], std::uint32_t(i), __ATOMIC_RELAXED);
  std::vector<std::size_t> order;
  order.reserve(id.size());
  for (std::uint32_t row : row_of)
    if (row != kNoRow) order.push_back(row);
  if (order.size() != id.size()) order.clear();  // a repeated id
  return order;
}

// Any ids: a stable least-significant-digit radix sort in two passes of 16 bits.
std::vector<std::size_t> radix_sorted(const std::vector<ParticleId>& id) {
  constexpr std::size_t kBins = std::size_t(1) << 16;
  std::vector<std::size_t> order(id.size()), next(id.size());
  for (std::size_t i = 0; i < id.size(); ++i) order[i] = i;
  for (int shift : {0, 16}) {
    std::vector<std::size_t> start(kBins + 1, 0);
    for (ParticleId x : id) ++start[((x >> shift) & 0xFFFFu) + 1];
    for (std::size_t b = 0; b < kBins; ++b) start[b + 1] += start[b];
    for (std::size_t i : order) next[start[(id[i] >> shift) & 0xFFFFu]++] = i;
    order.swap(next);
  }
  return order;
}

}  // namespace

std::vector<std::size_t> id_order(const std::vector<ParticleId>& id) {
  static_assert(sizeof(ParticleId) == 4, "radix_sorted sorts 32-bit ids");
  if (id.empty()) return {};
  const auto [lowest, highest] = std::minmax_element(id.begin(), id.end());
  const std::size_t range = std::size_t(*highest) - std::size_t(*lowest) + 1;
  if (range <= 4 * id.size() + 1024 && id.size() < kNoRow) {
    std::vector<std::size_t> order = scattered_by_id(id, *lowest, range);
    if (!order.empty()) return order;
  }
  return radix_sorted(id);
}

}  // namespace gs
