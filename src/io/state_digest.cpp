#include "io/state_digest.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "io/fnv1a.hpp"

namespace gs {

namespace {

bool bits_nonzero(double v) { return v != 0 || std::signbit(v); }  // -0.0 and NaN count
bool bits_nonzero(const Vec3d& v) { return bits_nonzero(v.x) || bits_nonzero(v.y) || bits_nonzero(v.z); }

// Whether entry e of `history` holds a contact that counts: a partner, and
// some kept field not +0 (a contact with zero springs continues exactly as a
// new one, which starts from zero: contact/contact_slots.hpp).
bool holds_contact(const HostHistory& history, std::size_t e) {
  if (history.partner[e] == kNoPartner) return false;
  bool state = false;
  for_each_history_field(history, [&](const char*, unsigned, const auto& field) {
    if (!field.empty() && bits_nonzero(field[e])) state = true;
  });
  return state;
}

}  // namespace

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
  std::vector<std::size_t> contacts;  // one particle's entries, by ascending partner id
  for (std::size_t r : order) {
    for_each_particle_field(s, [&](const char*, const auto& field) { add_row(field, r); });
    add_row(s.force, r), add_row(s.torque, r);
    if (history.partner.empty()) continue;
    contacts.clear();
    for (std::size_t k = 0; k < slots; ++k)
      if (holds_contact(history, r * slots + k)) contacts.push_back(r * slots + k);
    std::sort(contacts.begin(), contacts.end(),
              [&](std::size_t a, std::size_t b) { return history.partner[a] < history.partner[b]; });
    h.add_value(std::uint64_t(contacts.size()));
    for (std::size_t e : contacts) {
      h.add_value(history.partner[e]);
      for_each_history_field(history, [&](const char*, unsigned, const auto& field) { add_row(field, e); });
    }
  }
  return h.value();
}

}  // namespace gs
