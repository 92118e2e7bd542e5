#pragma once
// Out-of-line members of StepKernelsImpl: data movement (reorder, history
// transfer) kept apart from the physics above.
#include <stdexcept>

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

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::reorder_by_cells(ParticleStore& s) {
  if (s.n_ghost != 0) throw std::logic_error("reorder_by_cells needs a cell list of owned particles only");
  verlet_.valid = false;
  const Index n = s.n_owned;
  const Index* order = cells_.sorted.data();
  DeviceArray<unsigned char>& tmp = staging_;
  gather_in_place<Exec>(s.id, order, n, tmp);
  gather_in_place<Exec>(s.material, order, n, tmp);
  gather_in_place<Exec>(s.marker, order, n, tmp);
  gather_in_place<Exec>(s.radius, order, n, tmp);
  gather_in_place<Exec>(s.mass, order, n, tmp);
  gather_in_place<Exec>(s.inertia, order, n, tmp);
  gather_in_place<Exec>(s.position, order, n, tmp);
  gather_in_place<Exec>(s.velocity, order, n, tmp);
  gather_in_place<Exec>(s.angular_velocity, order, n, tmp);
  gather_in_place<Exec>(s.orientation, order, n, tmp);
  gather_in_place<Exec>(forces_.force, order, n, tmp);
  if (kTorque) gather_in_place<Exec>(forces_.torque, order, n, tmp);
  if (kHistory) {
    gather_slots_in_place<Exec>(history_.partner, order, n, history_.slots, history_.strides, tmp);
    gather_slots_in_place<Exec>(history_.tangential, order, n, history_.slots, history_.strides, tmp);
    gather_slots_in_place<Exec>(history_.rolling, order, n, history_.slots, history_.strides, tmp);
  }
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::upload_pairs(const PairTableHost& t) {
  n_materials_ = t.n_materials;
  std::vector<PairParams<Real>> p(std::size_t(t.n_materials) * t.n_materials);
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = pair_params<Real>(t, k);
  pairs_.from_host(p);
}

// Growing the capacity changes the strides of a slot-major history: the
// entries are re-laid out (new particles start with free slots).
template <class Exec, class Real, ContactModel Model, unsigned Effects>
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
  if (Effects & kFriction) relayout(history_.tangential, Vec3<Real>());
  if (Effects & kRollingResistance) relayout(history_.rolling, Vec3<Real>());
  history_.capacity = capacity;
  history_.strides = fresh_strides;
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
HostHistory StepKernelsImpl<Exec, Real, Model, Effects>::history(const ParticleStore& s) const {
  HostHistory h;
  h.slots = history_.slots;
  if (!kHistory) return h;
  const Index n = s.n_owned;
  const HistoryStrides at = history_.strides;
  const std::size_t slots = std::size_t(h.slots);
  const std::vector<ParticleId> partner = history_.partner.to_host();
  const std::vector<Vec3<Real>> tangential = history_.tangential.to_host();
  const std::vector<Vec3<Real>> rolling = history_.rolling.to_host();
  // Springs only of the effects the scene has: a checkpoint of a frictional
  // bed without rolling resistance carries no rolling zeros.
  h.partner.resize(n * slots);
  h.tangential.resize(tangential.empty() ? 0 : n * slots);
  h.rolling.resize(rolling.empty() ? 0 : n * slots);
  for (Index i = 0; i < n; ++i)
    for (std::size_t k = 0; k < slots; ++k) {
      const std::size_t e = at.at(int(k), std::size_t(i));
      h.partner[i * slots + k] = partner[e];
      if (!tangential.empty()) h.tangential[i * slots + k] = Vec3d(tangential[e]);
      if (!rolling.empty()) h.rolling[i * slots + k] = Vec3d(rolling[e]);
    }
  return h;
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
std::vector<std::uint16_t> StepKernelsImpl<Exec, Real, Model, Effects>::contact_counts(const ParticleStore& s) const {
  if (!kHistory) return std::vector<std::uint16_t>(std::size_t(s.n_owned), 0);
  DeviceArray<std::uint16_t> count(Exec::backend, std::size_t(s.n_owned));
  Exec::parallel_for(s.n_owned, CountContacts{history_.partner.data(), history_.strides, history_.slots, count.data()});
  return count.to_host();
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::set_history(const ParticleStore& s, const HostHistory& h) {
  if (!kHistory) return;
  if (h.slots != history_.slots)
    throw std::runtime_error("contact history has " + std::to_string(h.slots) + " slots per particle, this run uses " +
                             std::to_string(history_.slots));
  reserve(s.size());
  const HistoryStrides at = history_.strides;
  const std::size_t slots = std::size_t(h.slots), entries = slots * history_.capacity;
  std::vector<ParticleId> partner(entries, kNoPartner);
  std::vector<Vec3<Real>> tangential(entries), rolling(entries);
  for (Index i = 0; i < s.n_owned; ++i)
    for (std::size_t k = 0; k < slots; ++k) {
      const std::size_t e = at.at(int(k), std::size_t(i));
      partner[e] = h.partner[i * slots + k];
      if (!h.tangential.empty()) tangential[e] = Vec3<Real>(h.tangential[i * slots + k]);
      if (!h.rolling.empty()) rolling[e] = Vec3<Real>(h.rolling[i * slots + k]);
    }
  history_.partner.from_host(partner);
  if (Effects & kFriction) history_.tangential.from_host(tangential);
  if (Effects & kRollingResistance) history_.rolling.from_host(rolling);
}

}  // namespace gs
