#pragma once
// Out-of-line members of StepKernelsImpl: data movement (reorder, history
// transfer) kept apart from the physics above.
#include <stdexcept>
#include <type_traits>

namespace gs {

template <class Exec, class T>
void gather_in_place(DeviceArray<T>& a, const Index* order, Index n, DeviceArray<unsigned char>& scratch) {
  scratch.resize(std::size_t(n) * sizeof(T));
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
  scratch.resize(std::size_t(n) * sizeof(T));
  T* tmp = reinterpret_cast<T*>(scratch.data());
  const std::size_t step = strides.particle_stride;
  for (int s = 0; s < slots; ++s) {
    T* column = a.data() + strides.at(s, 0);
    Exec::parallel_for(n, GatherStrided<T>{column, step, tmp, 1, order});
    if (step == 1) backend_copy(Exec::backend, column, tmp, std::size_t(n) * sizeof(T));
    else Exec::parallel_for(n, GatherStrided<T>{tmp, 1, column, step, nullptr});
  }
}

template <class Exec, class Real, class Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::reorder_by_cells(ParticleStore& s) {
  if (s.n_ghost != 0) throw std::logic_error("reorder_by_cells needs a cell list of owned particles only");
  verlet_.valid = false;
  const Index n = s.n_owned;
  keep_in_order(s, cells_.sorted.data(), n);
}

// Owned particles order[0, n) become [0, n), with their forces and history.
template <class Exec, class Real, class Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::keep_in_order(ParticleStore& s, const Index* order, Index n) {
  DeviceArray<unsigned char>& tmp = staging_;
  for_each_particle_field(s, [&](const char*, auto& a) { gather_in_place<Exec>(a, order, n, tmp); });
  gather_in_place<Exec>(forces_.force, order, n, tmp);
  if (kTorque) gather_in_place<Exec>(forces_.torque, order, n, tmp);
  if (kHistory) {
    gather_slots_in_place<Exec>(history_.partner, order, n, history_.slots, history_.strides, tmp);
    for_each_history_field(history_, [&](const char*, unsigned, auto& a) {
      gather_slots_in_place<Exec>(a, order, n, history_.slots, history_.strides, tmp);
    });
  }
}

// Growing the capacity changes the strides of a slot-major history: the
// entries are re-laid out (new particles start with free slots).
template <class Exec, class Real, class Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::grow_history(std::size_t capacity) {
  const std::size_t old_capacity = history_.capacity;
  const HistoryStrides old = history_.strides;
  const HistoryStrides fresh_strides = HistoryStrides::of(Exec::history_order, history_.slots, capacity);
  const int slots = history_.slots;
  auto relayout = [&](auto& a, auto empty) {
    const auto host = a.to_host();
    std::vector<decltype(empty)> fresh(std::size_t(slots) * capacity, empty);
    for (int s = 0; s < slots; ++s)
      for (std::size_t i = 0; i < old_capacity; ++i) fresh[fresh_strides.at(s, i)] = host[old.at(s, i)];
    a.from_host(fresh);
  };
  relayout(history_.partner, kNoPartner);
  for_each_history_field(history_, [&](const char*, unsigned bit, auto& a) {
    if (kKept & bit) relayout(a, typename std::decay_t<decltype(a)>::value_type{});
  });
  history_.capacity = capacity;
  history_.strides = fresh_strides;
}

template <class Exec, class Real, class Model, unsigned Effects>
HostHistory StepKernelsImpl<Exec, Real, Model, Effects>::history(const ParticleStore& s) const {
  HostHistory h;
  h.slots = history_.slots;
  if (!kHistory) return h;
  const Index n = s.n_owned;
  const HistoryStrides at = history_.strides;
  const std::size_t slots = std::size_t(h.slots);
  // Rows i * slots + k from the layout of `at`, widened to fp64. Only the
  // fields the run keeps: a checkpoint of a frictional bed without rolling
  // resistance carries no rolling zeros.
  auto rows = [&](const auto& field, auto& out) {
    const auto device = field.to_host();
    out.resize(device.empty() ? 0 : n * slots);
    for (Index i = 0; i < n && !device.empty(); ++i)
      for (std::size_t k = 0; k < slots; ++k)
        out[i * slots + k] = typename std::decay_t<decltype(out)>::value_type(device[at.at(int(k), std::size_t(i))]);
  };
  rows(history_.partner, h.partner);
  for_each_history_field(history_, h, [&](const char*, unsigned, const auto& field, auto& out) { rows(field, out); });
  return h;
}

template <class Exec, class Real, class Model, unsigned Effects>
std::vector<std::uint16_t> StepKernelsImpl<Exec, Real, Model, Effects>::contact_counts(const ParticleStore& s) const {
  if (!kHistory) return std::vector<std::uint16_t>(std::size_t(s.n_owned), 0);
  DeviceArray<std::uint16_t> count(Exec::backend, std::size_t(s.n_owned));
  Exec::parallel_for(s.n_owned, CountContacts{history_.partner.data(), history_.strides, history_.slots, count.data()});
  return count.to_host();
}

template <class Exec, class Real, class Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::set_history(const ParticleStore& s, const HostHistory& h) {
  if (!kHistory) return;
  if (h.slots != history_.slots)
    throw std::runtime_error("contact history has " + std::to_string(h.slots) + " slots per particle, this run uses " +
                             std::to_string(history_.slots));
  reserve(s.size());
  const HistoryStrides at = history_.strides;
  const std::size_t slots = std::size_t(h.slots), entries = slots * history_.capacity;
  // The layout of `at` from rows i * slots + k, narrowed to the force precision.
  auto layout = [&](const auto& rows, auto& field, auto empty) {
    std::vector<decltype(empty)> device(entries, empty);
    for (Index i = 0; i < s.n_owned && !rows.empty(); ++i)
      for (std::size_t k = 0; k < slots; ++k)
        device[at.at(int(k), std::size_t(i))] = decltype(empty)(rows[i * slots + k]);
    field.from_host(device);
  };
  layout(h.partner, history_.partner, kNoPartner);
  for_each_history_field(h, history_, [&](const char*, unsigned bit, const auto& rows, auto& field) {
    if (kKept & bit) layout(rows, field, typename std::decay_t<decltype(field)>::value_type{});
  });
}

}  // namespace gs
