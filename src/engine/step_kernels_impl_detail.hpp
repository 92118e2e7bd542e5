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

template <class Exec, class T>
void gather_slots_in_place(DeviceArray<T>& a, const Index* order, Index n, int slots, std::size_t stride,
                           DeviceArray<unsigned char>& scratch) {
  if (a.size() == 0) return;
  scratch.resize(a.size() * sizeof(T));
  T* tmp = reinterpret_cast<T*>(scratch.data());
  Exec::parallel_for(Index(slots) * n, GatherSlots<T>{a.data(), tmp, order, stride, n});
  Exec::parallel_for(Index(slots) * n, GatherSlots<T>{tmp, a.data(), nullptr, stride, n});
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::reorder_by_cells(ParticleStore& s) {
  if (s.n_ghost != 0) throw std::logic_error("reorder_by_cells needs a cell list of owned particles only");
  const Index n = s.n_owned;
  const Index* order = cells_.sorted.data();
  DeviceArray<unsigned char> tmp(Exec::backend);
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
    gather_slots_in_place<Exec>(history_.partner, order, n, history_.slots, history_.stride, tmp);
    gather_slots_in_place<Exec>(history_.tangential, order, n, history_.slots, history_.stride, tmp);
    gather_slots_in_place<Exec>(history_.rolling, order, n, history_.slots, history_.stride, tmp);
  }
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::upload_pairs(const PairTableHost& t) {
  n_materials_ = t.n_materials;
  std::vector<PairParams<Real>> p(std::size_t(t.n_materials) * t.n_materials);
  for (std::size_t k = 0; k < p.size(); ++k) {
    p[k] = PairParams<Real>{Real(t.stiffness_normal[k]),   Real(t.stiffness_tangential[k]),
                            Real(t.stiffness_rolling[k]),  Real(t.damping_ratio[k]),
                            Real(t.friction[k]),           Real(t.rolling_friction[k]),
                            Real(t.cohesion[k]),           Real(t.youngs_modulus_eff[k]),
                            Real(t.shear_modulus_eff[k])};
  }
  pairs_.from_host(p);
}

// History is slot-major with stride = capacity: growing re-lays it out.
template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::grow_history(std::size_t stride) {
  const std::size_t old_stride = history_.stride;
  const std::size_t slots = std::size_t(history_.slots);
  auto relayout_partner = [&]() {
    std::vector<ParticleId> host = history_.partner.to_host();
    std::vector<ParticleId> fresh(slots * stride, kNoPartner);
    for (std::size_t s = 0; s < slots; ++s)
      for (std::size_t i = 0; i < old_stride; ++i) fresh[s * stride + i] = host[s * old_stride + i];
    history_.partner.from_host(fresh);
  };
  auto relayout_springs = [&](DeviceArray<Vec3<Real>>& a) {
    std::vector<Vec3<Real>> host = a.to_host();
    std::vector<Vec3<Real>> fresh(slots * stride);
    for (std::size_t s = 0; s < slots; ++s)
      for (std::size_t i = 0; i < old_stride; ++i) fresh[s * stride + i] = host[s * old_stride + i];
    a.from_host(fresh);
  };
  relayout_partner();
  if (Effects & kFriction) relayout_springs(history_.tangential);
  if (Effects & kRollingResistance) relayout_springs(history_.rolling);
  history_.stride = stride;
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
HostHistory StepKernelsImpl<Exec, Real, Model, Effects>::history(const ParticleStore& s) const {
  HostHistory h;
  h.slots = history_.slots;
  if (!kHistory) return h;
  const Index n = s.n_owned;
  const std::size_t stride = history_.stride, slots = std::size_t(h.slots);
  const std::vector<ParticleId> partner = history_.partner.to_host();
  const std::vector<Vec3<Real>> tangential = history_.tangential.to_host();
  const std::vector<Vec3<Real>> rolling = history_.rolling.to_host();
  h.partner.resize(n * slots);
  h.tangential.resize(n * slots);
  h.rolling.resize(n * slots);
  for (Index i = 0; i < n; ++i)
    for (std::size_t k = 0; k < slots; ++k) {
      h.partner[i * slots + k] = partner[k * stride + i];
      if (!tangential.empty()) h.tangential[i * slots + k] = Vec3d(tangential[k * stride + i]);
      if (!rolling.empty()) h.rolling[i * slots + k] = Vec3d(rolling[k * stride + i]);
    }
  return h;
}

template <class Exec, class Real, ContactModel Model, unsigned Effects>
void StepKernelsImpl<Exec, Real, Model, Effects>::set_history(const ParticleStore& s, const HostHistory& h) {
  if (!kHistory) return;
  if (h.slots != history_.slots)
    throw std::runtime_error("contact history has " + std::to_string(h.slots) + " slots per particle, this run uses " +
                             std::to_string(history_.slots));
  reserve(s.size());
  const std::size_t stride = history_.stride, slots = std::size_t(h.slots);
  std::vector<ParticleId> partner(slots * stride, kNoPartner);
  std::vector<Vec3<Real>> tangential(slots * stride), rolling(slots * stride);
  for (Index i = 0; i < s.n_owned; ++i)
    for (std::size_t k = 0; k < slots; ++k) {
      partner[k * stride + i] = h.partner[i * slots + k];
      if (!h.tangential.empty()) tangential[k * stride + i] = Vec3<Real>(h.tangential[i * slots + k]);
      if (!h.rolling.empty()) rolling[k * stride + i] = Vec3<Real>(h.rolling[i * slots + k]);
    }
  history_.partner.from_host(partner);
  if (Effects & kFriction) history_.tangential.from_host(tangential);
  if (Effects & kRollingResistance) history_.rolling.from_host(rolling);
}

}  // namespace gs
