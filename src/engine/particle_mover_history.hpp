#pragma once
// Out-of-line members of ParticleMover: re-sorting the store, laying the
// history out, and the history from the host.
#include <stdexcept>
#include <type_traits>

namespace gs {

template <class Exec, class T>
void gather_in_place(DeviceArray<T>& a, const Index* order, Index n, DeviceArray<unsigned char>& scratch) {
  scratch.resize_discarding(std::size_t(n) * sizeof(T));
  T* tmp = reinterpret_cast<T*>(scratch.data());
  Exec::parallel_for(n, Gather<T>{a.data(), tmp, order});
  backend_copy(Exec::backend, a.data(), tmp, std::size_t(n) * sizeof(T));
}

// to[k * to_stride] = from[order[k] * from_stride] (order null: k).
template <class T>
struct GatherStrided {
  const T* from;
  std::size_t from_stride;
  T* to;
  std::size_t to_stride;
  const Index* order;
  GS_HD void operator()(Index k) const {
    const std::size_t source = std::size_t(order ? order[k] : k);
    to[std::size_t(k) * to_stride] = from[source * from_stride];
  }
};

// One slot at a time, so the scratch is one particle array, not the whole
// history (this keeps the peak memory of a step near what the run holds).
// A slot's entries are `particle_stride` apart; slot-major makes them contiguous.
template <class Exec, class T>
void gather_slots_in_place(DeviceArray<T>& a, const Index* order, Index n, int slots, const HistoryStrides& strides,
                           DeviceArray<unsigned char>& scratch) {
  if (a.size() == 0) return;
  scratch.resize_discarding(std::size_t(n) * sizeof(T));
  T* tmp = reinterpret_cast<T*>(scratch.data());
  const std::size_t step = strides.particle_stride;
  for (int s = 0; s < slots; ++s) {
    T* column = a.data() + strides.at(s, 0);
    Exec::parallel_for(n, GatherStrided<T>{column, step, tmp, 1, order});
    if (step == 1) backend_copy(Exec::backend, column, tmp, std::size_t(n) * sizeof(T));
    else Exec::parallel_for(n, GatherStrided<T>{tmp, 1, column, step, nullptr});
  }
}

template <class Exec, class Real>
void ParticleMover<Exec, Real>::reorder(ParticleStore& s, const DeviceArray<Index>& order) {
  if (s.n_ghost != 0 || order.size() != std::size_t(s.n_owned))
    throw std::logic_error("reorder needs one store index per owned particle and no ghosts");
  keep_in_order(s, order.data(), s.n_owned);
}

// Owned particles order[0, n) become [0, n), with their forces and history
// (the surface slots gathered, the pair history's origins: engine/pair_carry.hpp).
template <class Exec, class Real>
void ParticleMover<Exec, Real>::keep_in_order(ParticleStore& s, const Index* order, Index n) {
  DeviceArray<unsigned char>& tmp = st_.staging;
  s.begin_change();
  for_each_kept_particle_field(s, s.fields_kept, [&](const char*, auto& a) { gather_in_place<Exec>(a, order, n, tmp); });
  gather_in_place<Exec>(st_.forces.force, order, n, tmp);
  if (st_.torque) gather_in_place<Exec>(st_.forces.torque, order, n, tmp);
  if (st_.keeps_history()) {
    gather_slots_in_place<Exec>(st_.history.partner, order, n, st_.history.slots, st_.history.strides, tmp);
    for_each_history_field(st_.history, [&](const char*, unsigned, auto& a) {
      gather_slots_in_place<Exec>(a, order, n, st_.history.slots, st_.history.strides, tmp);
    });
    pairs_.permute(order, n, tmp);
  }
}

// Row i of a history in the layout `fresh`: the entries of `old` for
// particles below old_capacity, `empty` beyond (free slots).
template <class T>
struct RelayoutRow {
  const T* from;
  T* to;
  HistoryStrides old, fresh;
  Index old_capacity;
  int slots;
  T empty;
  GS_HD void operator()(Index i) const {
    const std::size_t p = std::size_t(i);
    for (int s = 0; s < slots; ++s) to[fresh.at(s, p)] = i < old_capacity ? from[old.at(s, p)] : empty;
  }
};

// Growing the capacity changes the strides of a slot-major history: the
// entries are re-laid out (new particles start with free slots) on the
// backend. (Through the host, as it once was, a GPU run of 3e8 particles
// spent most of its set-up filling 58 GB of empty history there.)
template <class Exec, class Real>
void ParticleMover<Exec, Real>::grow_history(std::size_t capacity) {
  ContactHistory<Real>& h = st_.history;
  const HistoryStrides old = h.strides;
  const HistoryStrides fresh = HistoryStrides::of(Exec::history_order, h.slots, capacity);
  auto relayout = [&](auto& a, auto empty) {
    using T = decltype(empty);
    DeviceArray<T> grown(Exec::backend, std::size_t(h.slots) * capacity);
    Exec::parallel_for(Index(capacity),
                       RelayoutRow<T>{a.data(), grown.data(), old, fresh, Index(h.capacity), h.slots, empty});
    a = std::move(grown);
  };
  relayout(h.partner, kNoPartner);
  for_each_history_field(h, [&](const char*, unsigned bit, auto& a) {
    if (st_.kept & bit) relayout(a, typename std::decay_t<decltype(a)>::value_type{});
  });
  h.capacity = capacity;
  h.strides = fresh;
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

// Host rows of particles [first, first + rows) as arrivals (engine/pair_carry.hpp),
// through packed slot-major blocks in backend memory in the force precision.
template <class Exec, class Real>
void ParticleMover<Exec, Real>::arrive_from_host(const ParticleStore& s, Index first, const HostHistory& h) {
  const std::size_t slots = std::size_t(h.slots);
  const std::size_t count = slots == 0 ? 0 : h.partner.size() / slots;
  if (count == 0) return;
  auto block_of = [&](const auto& rows, auto& device) {
    using T = typename std::decay_t<decltype(device)>::value_type;
    std::vector<T> block(slots * count);
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t k = 0; k < slots; ++k) block[k * count + i] = T(rows[i * slots + k]);
    device.from_host(block);
  };
  DeviceArray<ParticleId> partner(Exec::backend);
  block_of(h.partner, partner);
  ContactHistory<Real> fields;  // one block per kept field, in GS_HISTORY_FIELDS order
  const void* at[kHistoryFieldCount] = {};
  int f = 0;
  for_each_history_field(h, fields, [&](const char* name, unsigned bit, const auto& rows, auto& device) {
    device = std::decay_t<decltype(device)>(Exec::backend);
    if (st_.kept & bit) {
      if (rows.size() != h.partner.size())
        throw std::invalid_argument(std::string("contact history lacks the field ") + name + " this run keeps");
      block_of(rows, device);
      at[f] = device.data();
    }
    ++f;
  });
  pairs_.arrive(first, Index(count), partner.data(), at, s.id.data());
}

}  // namespace gs
