#pragma once
// Out-of-line members of StepKernelsImpl that move particles between ranks:
// gather into packed buffers, compact, append. Pure data movement, run as
// backend kernels; values are copied bit for bit.
#include <stdexcept>

namespace gs {

// History entries of particles `which`, laid out as `strides` says, into a
// packed slot-major block with stride m.
template <class T>
struct GatherHistory {
  const T* from;
  T* to;
  const Index* which;
  HistoryStrides strides;
  Index m;
  GS_HD void operator()(Index k) const {
    const Index s = k / m, i = k % m;
    to[std::size_t(s) * std::size_t(m) + std::size_t(i)] = from[strides.at(s, std::size_t(which[i]))];
  }
};

// The inverse: a packed block of m particles written at [first, first + m).
template <class T>
struct ScatterHistory {
  const T* from;
  T* to;
  HistoryStrides strides;
  Index first;
  Index m;
  GS_HD void operator()(Index k) const {
    const Index s = k / m, i = k % m;
    to[strides.at(s, std::size_t(first + i))] = from[std::size_t(s) * std::size_t(m) + std::size_t(i)];
  }
};

// Staging buffers are the kernels' own (`scratch`), reused from call to call:
// allocating device memory every step would cost more than the copies.
template <class T>
T* staging(DeviceArray<unsigned char>& scratch, std::size_t n) {
  scratch.resize(n * sizeof(T));
  return reinterpret_cast<T*>(scratch.data());
}

template <class Exec, class T>
std::vector<T> gathered_to_host(const DeviceArray<T>& a, const DeviceArray<Index>& which,
                                DeviceArray<unsigned char>& scratch) {
  const Index m = Index(which.size());
  T* packed = staging<T>(scratch, std::size_t(m));
  Exec::parallel_for(m, Gather<T>{a.data(), packed, which.data()});
  std::vector<T> h(static_cast<std::size_t>(m));
  if (m > 0) backend_copy_to_host(Exec::backend, h.data(), packed, h.size() * sizeof(T));
  return h;
}

template <class Exec, class T>
std::vector<T> gathered_history_to_host(const DeviceArray<T>& a, const DeviceArray<Index>& which, int slots,
                                        const HistoryStrides& strides, DeviceArray<unsigned char>& scratch) {
  const Index m = Index(which.size());
  const std::size_t n = std::size_t(slots) * std::size_t(m);
  T* packed = staging<T>(scratch, n);
  Exec::parallel_for(Index(slots) * m, GatherHistory<T>{a.data(), packed, which.data(), strides, m});
  std::vector<T> h(n);
  if (n > 0) backend_copy_to_host(Exec::backend, h.data(), packed, n * sizeof(T));
  return h;
}

template <class Exec, class T>
void scatter_history_from_host(DeviceArray<T>& a, const std::vector<T>& block, int slots, const HistoryStrides& strides,
                               Index first, DeviceArray<unsigned char>& scratch) {
  const Index m = Index(block.size() / std::size_t(slots));
  T* packed = staging<T>(scratch, block.size());
  if (!block.empty()) backend_copy_from_host(Exec::backend, packed, block.data(), block.size() * sizeof(T));
  Exec::parallel_for(Index(slots) * m, ScatterHistory<T>{packed, a.data(), strides, first, m});
}

template <class T>
void append_from_host(DeviceArray<T>& a, const std::vector<T>& h, std::size_t first) {
  a.resize(first + h.size());
  if (!h.empty()) backend_copy_from_host(a.backend(), a.data() + first, h.data(), h.size() * sizeof(T));
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
ParticleRecords StepKernelsImpl<Exec, Real, Model, Effects>::export_particles(const ParticleStore& s,
                                                                              const DeviceArray<Index>& w,
                                                                              bool with_history) const {
  ParticleRecords r;
  r.id = gathered_to_host<Exec>(s.id, w, staging_);
  r.material = gathered_to_host<Exec>(s.material, w, staging_);
  r.marker = gathered_to_host<Exec>(s.marker, w, staging_);
  r.radius = gathered_to_host<Exec>(s.radius, w, staging_);
  r.mass = gathered_to_host<Exec>(s.mass, w, staging_);
  r.inertia = gathered_to_host<Exec>(s.inertia, w, staging_);
  r.position = gathered_to_host<Exec>(s.position, w, staging_);
  r.velocity = gathered_to_host<Exec>(s.velocity, w, staging_);
  r.angular_velocity = gathered_to_host<Exec>(s.angular_velocity, w, staging_);
  r.orientation = gathered_to_host<Exec>(s.orientation, w, staging_);
  if (!with_history || !kHistory) return r;

  const std::size_t m = w.size(), slots = std::size_t(history_.slots);
  HostHistory& h = r.history;
  h.slots = history_.slots;
  const std::vector<ParticleId> partner =
      gathered_history_to_host<Exec>(history_.partner, w, history_.slots, history_.strides, staging_);
  h.partner.resize(m * slots);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < slots; ++k) h.partner[i * slots + k] = partner[k * m + i];
  auto widen_springs = [&](const DeviceArray<Vec3<Real>>& a, std::vector<Vec3d>& out) {
    const std::vector<Vec3<Real>> block = gathered_history_to_host<Exec>(a, w, history_.slots, history_.strides, staging_);
    out.resize(m * slots);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t k = 0; k < slots; ++k) out[i * slots + k] = Vec3d(block[k * m + i]);
  };
  if constexpr ((Effects & kFriction) != 0) widen_springs(history_.tangential, h.tangential);
  if constexpr ((Effects & kRollingResistance) != 0) widen_springs(history_.rolling, h.rolling);
  return r;
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::keep_owned(ParticleStore& s, const DeviceArray<Index>& order) {
  const Index n = Index(order.size());
  DeviceArray<unsigned char>& tmp = staging_;
  gather_in_place<Exec>(s.id, order.data(), n, tmp);
  gather_in_place<Exec>(s.material, order.data(), n, tmp);
  gather_in_place<Exec>(s.marker, order.data(), n, tmp);
  gather_in_place<Exec>(s.radius, order.data(), n, tmp);
  gather_in_place<Exec>(s.mass, order.data(), n, tmp);
  gather_in_place<Exec>(s.inertia, order.data(), n, tmp);
  gather_in_place<Exec>(s.position, order.data(), n, tmp);
  gather_in_place<Exec>(s.velocity, order.data(), n, tmp);
  gather_in_place<Exec>(s.angular_velocity, order.data(), n, tmp);
  gather_in_place<Exec>(s.orientation, order.data(), n, tmp);
  gather_in_place<Exec>(forces_.force, order.data(), n, tmp);
  if (kTorque) gather_in_place<Exec>(forces_.torque, order.data(), n, tmp);
  if (kHistory) {
    gather_slots_in_place<Exec>(history_.partner, order.data(), n, history_.slots, history_.strides, tmp);
    gather_slots_in_place<Exec>(history_.tangential, order.data(), n, history_.slots, history_.strides, tmp);
    gather_slots_in_place<Exec>(history_.rolling, order.data(), n, history_.slots, history_.strides, tmp);
  }
  s.n_owned = n;
  s.drop_ghosts();
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::append(ParticleStore& s, const ParticleRecords& r, bool as_ghosts) {
  if (!as_ghosts && s.n_ghost != 0) throw std::logic_error("owned particles can only be appended before ghosts");
  const std::size_t first = std::size_t(s.size());
  append_from_host(s.id, r.id, first);
  append_from_host(s.material, r.material, first);
  append_from_host(s.marker, r.marker, first);
  append_from_host(s.radius, r.radius, first);
  append_from_host(s.mass, r.mass, first);
  append_from_host(s.inertia, r.inertia, first);
  append_from_host(s.position, r.position, first);
  append_from_host(s.velocity, r.velocity, first);
  append_from_host(s.angular_velocity, r.angular_velocity, first);
  append_from_host(s.orientation, r.orientation, first);
  const Index m = Index(r.size());
  if (as_ghosts) s.n_ghost += m;
  else s.n_owned += m;
  reserve(s.size());
  if (as_ghosts || !kHistory || m == 0) return;

  const HostHistory& h = r.history;
  if (h.slots != history_.slots)
    throw std::runtime_error("arriving particles carry " + std::to_string(h.slots) + " history slots, this run uses " +
                             std::to_string(history_.slots));
  const std::size_t slots = std::size_t(h.slots), count = std::size_t(m);
  std::vector<ParticleId> partner(slots * count);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t k = 0; k < slots; ++k) partner[k * count + i] = h.partner[i * slots + k];
  scatter_history_from_host<Exec>(history_.partner, partner, h.slots, history_.strides, Index(first), staging_);
  auto narrow_springs = [&](const std::vector<Vec3d>& from, DeviceArray<Vec3<Real>>& a) {
    std::vector<Vec3<Real>> block(slots * count);
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t k = 0; k < slots; ++k) block[k * count + i] = Vec3<Real>(from[i * slots + k]);
    scatter_history_from_host<Exec>(a, block, h.slots, history_.strides, Index(first), staging_);
  };
  if constexpr ((Effects & kFriction) != 0) narrow_springs(h.tangential, history_.tangential);
  if constexpr ((Effects & kRollingResistance) != 0) narrow_springs(h.rolling, history_.rolling);
}

}  // namespace gs
