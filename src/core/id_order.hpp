#pragma once
// Particles in ascending id order, in linear time: output, checkpoints and
// analyses see particles by id, whatever order memory holds them in. Ids are
// unique and nearly dense (0..N-1 with the gaps that removals leave), so a
// scatter by id does what a comparison sort would in O(N log N).
#include <cstddef>
#include <vector>

#include "core/types.hpp"

namespace gs {

// order[r] is the index in `id` of the r-th smallest id. Equal ids (not in a
// run, but a caller may pass them) keep their order of appearance.
std::vector<std::size_t> id_order(const std::vector<ParticleId>& id);

// Row r of the result is v[order[r]] (order as id_order gives it).
template <class T>
std::vector<T> permuted(const std::vector<T>& v, const std::vector<std::size_t>& order) {
  std::vector<T> out(order.size());
  const auto n = static_cast<std::ptrdiff_t>(order.size());
#pragma omp parallel for schedule(static) if (n > 100000)
  for (std::ptrdiff_t r = 0; r < n; ++r) out[std::size_t(r)] = v[order[std::size_t(r)]];
  return out;
}

}  // namespace gs
