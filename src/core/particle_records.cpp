#include "core/particle_records.hpp"

#include <cstddef>

namespace gs {

HostHistory rows_permuted(const HostHistory& h, const std::vector<std::size_t>& order) {
  const std::size_t k = std::size_t(h.slots);
  // Rows are independent: any thread may copy any of them (a copy, no sum).
  auto rows = [&](const auto& from, auto& to) {
    to.assign(from.empty() ? 0 : order.size() * k, {});
    if (from.empty()) return;
    const auto n = static_cast<std::ptrdiff_t>(order.size());
#pragma omp parallel for schedule(static) if (n > 100000)
    for (std::ptrdiff_t r = 0; r < n; ++r)
      for (std::size_t s = 0; s < k; ++s) to[std::size_t(r) * k + s] = from[order[std::size_t(r)] * k + s];
  };
  HostHistory out;
  out.slots = h.slots;
  rows(h.partner, out.partner);
  for_each_history_field(h, out, [&](const char*, unsigned, const auto& from, auto& to) { rows(from, to); });
  return out;
}

}  // namespace gs
