#include "io/state_digest.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "io/fnv1a.hpp"

namespace gs {

std::uint64_t state_digest(const ParticleSnapshot& s, const HostHistory& history) {
  const std::size_t n = s.size(), slots = std::size_t(history.slots);
  if (!history.partner.empty() && history.partner.size() != n * slots)
    throw std::invalid_argument("state_digest: the history has " + std::to_string(history.partner.size()) +
                                " entries for " + std::to_string(n) + " particles of " + std::to_string(slots) +
                                " slots");
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s.id[a] < s.id[b]; });
  Fnv1a64 h;
  h.add_value(std::int64_t(s.step));
  h.add_value(s.time);
  h.add_value(std::uint64_t(n));
  auto add_row = [&](const auto& field, std::size_t r) {
    if (!field.empty()) h.add_value(field[r]);
  };
  for (std::size_t r : order) {
    for_each_particle_field(s, [&](const char*, const auto& field) { add_row(field, r); });
    add_row(s.force, r), add_row(s.torque, r);
    for (std::size_t k = 0; k < slots && !history.partner.empty(); ++k) {
      const std::size_t e = r * slots + k;
      h.add_value(history.partner[e]);
      for_each_history_field(history, [&](const char*, unsigned, const auto& field) { add_row(field, e); });
    }
  }
  return h.value();
}

}  // namespace gs
