#pragma once
// Out-of-line members of ParticleMover: re-sorting the store, laying the
// history out, and the history from the host.
#include <algorithm>
#include <stdexcept>
#include <type_traits>

namespace gs {

// A re-sort gathers each field into the staging buffer and copies it back.
// A field of three components (positions, velocities, forces) goes a
// component at a time where the staging buffer holds less than the whole
// field: a third of the room (8 bytes per particle for fp64, not 24), so the
// re-sort is not what sizes the staging buffer (engine/step_state.hpp).
// Component c's placing kernel also gathers component c + 1 (each thread
// touches only its own staging entry, and the components are disjoint), so
// a field takes four launches instead of a gather and a copy.
template <class T>
struct GatherComponent {  // to[k] = component c of particle order[k]
  const T* from;          // the field as n x 3 values
  T* to;
  const Index* order;
  int c;
  GS_HD void operator()(Index k) const { to[k] = from[3 * std::size_t(order[k]) + std::size_t(c)]; }
};

template <class T>
struct PlaceComponent {  // component c of particle k = tmp[k]; then tmp[k] = component c + 1 of order[k], if any
  T* field;
  T* tmp;
  const Index* order;
  int c;
  GS_HD void operator()(Index k) const {
    const T v = tmp[k];
    if (c < 2) tmp[k] = field[3 * std::size_t(order[k]) + std::size_t(c) + 1];
    field[3 * std::size_t(k) + std::size_t(c)] = v;
  }
};

template <class Exec, class T>
void gather_in_place(DeviceArray<T>& a, const Index* order, Index n, DeviceArray<unsigned char>& scratch) {
  scratch.resize_discarding(std::size_t(n) * sizeof(T));
  T* tmp = reinterpret_cast<T*>(scratch.data());
  Exec::parallel_for(n, Gather<T>{a.data(), tmp, order});
  backend_copy(Exec::backend, a.data(), tmp, std::size_t(n) * sizeof(T));
}

template <class Exec, class T>
void gather_in_place(DeviceArray<Vec3<T>>& a, const Index* order, Index n, DeviceArray<unsigned char>& scratch) {
  static_assert(sizeof(Vec3<T>) == 3 * sizeof(T), "a Vec3 is three values");
  if (scratch.bytes() >= std::size_t(n) * sizeof(Vec3<T>)) {
    scratch.resize_discarding(std::size_t(n) * sizeof(Vec3<T>));  // (no new storage)
    Vec3<T>* tmp = reinterpret_cast<Vec3<T>*>(scratch.data());
    Exec::parallel_for(n, Gather<Vec3<T>>{a.data(), tmp, order});
    backend_copy(Exec::backend, a.data(), tmp, std::size_t(n) * sizeof(Vec3<T>));
    return;
  }
  scratch.resize_discarding(std::size_t(n) * sizeof(T));
  T* tmp = reinterpret_cast<T*>(scratch.data());
  T* field = reinterpret_cast<T*>(a.data());
  Exec::parallel_for(n, GatherComponent<T>{field, tmp, order, 0});
  for (int c = 0; c < 3; ++c) Exec::parallel_for(n, PlaceComponent<T>{field, tmp, order, c});
}

template <class Exec, class Real>
void ParticleMover<Exec, Real>::reorder(ParticleStore& s, const DeviceArray<Index>& order) {
  if (s.n_ghost != 0 || order.size() != std::size_t(s.n_owned))
    throw std::logic_error("reorder needs one store index per owned particle and no ghosts");
  keep_in_order(s, order.data(), s.n_owned);
}

// Owned particles order[0, n) become [0, n), with their forces and history
// (their surface rows, the pair history's origins: engine/pair_carry.hpp).
template <class Exec, class Real>
void ParticleMover<Exec, Real>::keep_in_order(ParticleStore& s, const Index* order, Index n) {
  DeviceArray<unsigned char>& tmp = st_.staging;
  s.begin_change();
  for_each_kept_particle_field(s, s.fields_kept, [&](const char*, auto& a) { gather_in_place<Exec>(a, order, n, tmp); });
  gather_in_place<Exec>(st_.forces.force, order, n, tmp);
  if (st_.torque) gather_in_place<Exec>(st_.forces.torque, order, n, tmp);
  if (st_.keeps_history()) {
    // The surface rows stay where they are; each particle takes its row's index along.
    st_.history.row.resize(std::size_t(n));
    gather_in_place<Exec>(st_.history.row, order, n, tmp);
    pairs_.permute(order, n, tmp);
  }
}

// Every owned particle's row (a restart's), before the first list is built.
template <class Exec, class Real>
void ParticleMover<Exec, Real>::set_history(const ParticleStore& s, const HostHistory& h) {
  if (!st_.keeps_history()) return;
  if (h.slots != st_.row_width)
    throw std::runtime_error("contact history has " + std::to_string(h.slots) + " slots per particle, this run uses " +
                             std::to_string(st_.row_width));
  if (st_.pairs.attached || st_.pairs.pending_rows != 0 || st_.pairs.origin.size() != 0)
    throw std::logic_error("set_history after the pair history was set");
  reserve(s.size());
  arrive_from_host(s, 0, h);
}

// The rows an arrival from the host moves through backend memory at a time:
// a 32nd of them, at least 1024 (192 KiB at 12 slots), so that a restart adds
// a few bytes per particle to what the pending table holds, in at most 32
// pieces (each a few launches and a read of a count).
inline std::size_t arrival_piece(std::size_t rows) {
  return std::max(std::size_t(1024), (rows + 31) / 32);
}

// Host rows of particles [first, first + rows) as arrivals (engine/pair_carry.hpp),
// through packed slot-major blocks in backend memory in the force precision,
// a piece of the rows at a time (arrival_piece): whole, a restart's rows
// (16 bytes a slot, most of them empty) would stand in backend memory beside
// the pending table their pair contacts go to (docs/PERFORMANCE.md, "A
// restart's contact rows in pieces"); the table is reserved for the pair
// contacts counted on the host.
template <class Exec, class Real>
void ParticleMover<Exec, Real>::arrive_from_host(const ParticleStore& s, Index first, const HostHistory& h) {
  const std::size_t slots = std::size_t(h.slots);
  const std::size_t count = slots == 0 ? 0 : h.partner.size() / slots;
  if (count == 0) return;
  for_each_history_field(h, [&](const char* name, unsigned bit, const auto& rows) {
    if ((st_.kept & bit) && rows.size() != h.partner.size())
      throw std::invalid_argument(std::string("contact history lacks the field ") + name + " this run keeps");
  });
  // Rows [c0, c0 + m) of `rows` into `device` as a slot-major block.
  auto block_of = [&](const auto& rows, auto& device, std::size_t c0, std::size_t m) {
    using T = typename std::decay_t<decltype(device)>::value_type;
    std::vector<T> block(slots * m);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t k = 0; k < slots; ++k) block[k * m + i] = T(rows[(c0 + i) * slots + k]);
    device.from_host(block);
  };
  const auto pairs = std::count_if(h.partner.begin(), h.partner.end(), names_particle);
  pairs_.reserve_arrivals(first, Index(count), std::size_t(pairs));
  DeviceArray<ParticleId> partner(Exec::backend);
  ContactHistory<Real> fields;  // one block per kept field, in GS_HISTORY_FIELDS order
  for_each_history_field(fields, [&](const char*, unsigned, auto& device) {
    device = std::decay_t<decltype(device)>(Exec::backend);
  });
  const std::size_t piece = arrival_piece(count);
  for (std::size_t c0 = 0; c0 < count; c0 += piece) {
    const std::size_t m = std::min(piece, count - c0);
    block_of(h.partner, partner, c0, m);
    const void* at[kHistoryFieldCount] = {};
    int f = 0;
    for_each_history_field(h, fields, [&](const char*, unsigned bit, const auto& rows, auto& device) {
      if (st_.kept & bit) {
        block_of(rows, device, c0, m);
        at[f] = device.data();
      }
      ++f;
    });
    pairs_.arrive(first + Index(c0), Index(m), partner.data(), at, s.id.data());
  }
}

}  // namespace gs
