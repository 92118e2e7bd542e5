#pragma once
// Out-of-line members of ParticleMover that move particles between ranks
// and from the host: gather into packed buffers, compact, append.
#include <stdexcept>
#include <string>
#include <type_traits>

#include "engine/particle_message.hpp"

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
  scratch.resize_discarding(n * sizeof(T));
  return reinterpret_cast<T*>(scratch.data());
}

// Field `a` of particles `which`, packed at `to`.
template <class Exec, class T>
void gather_into(const DeviceArray<T>& a, const DeviceArray<Index>& which, unsigned char* to) {
  Exec::parallel_for(Index(which.size()), Gather<T>{a.data(), reinterpret_cast<T*>(to), which.data()});
}

template <class Exec, class T>
void gather_history_into(const DeviceArray<T>& a, const DeviceArray<Index>& which, int slots,
                         const HistoryStrides& strides, unsigned char* to) {
  const Index m = Index(which.size());
  Exec::parallel_for(Index(slots) * m, GatherHistory<T>{a.data(), reinterpret_cast<T*>(to), which.data(), strides, m});
}

// Rows i * slots + s of a packed slot-major block of m particles.
template <class T>
std::vector<T> slot_major_to_rows(const std::vector<T>& block, int slots, std::size_t m) {
  std::vector<T> rows(block.size());
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t s = 0; s < std::size_t(slots); ++s) rows[i * std::size_t(slots) + s] = block[s * m + i];
  return rows;
}

template <class T>
struct CopyTo {
  const T* from;
  T* to;
  GS_HD void operator()(Index k) const { to[k] = from[k]; }
};

// m packed values at `from` into a[first, first + m) (a already that long).
template <class Exec, class T>
void scatter_from(const unsigned char* from, DeviceArray<T>& a, std::size_t first, Index m) {
  Exec::parallel_for(m, CopyTo<T>{reinterpret_cast<const T*>(from), a.data() + first});
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

template <class Exec, class Real>
MessageHeader ParticleMover<Exec, Real>::message_header(const ParticleStore& s, Index count,
                                                        bool with_history) const {
  MessageHeader h;
  h.count = std::uint64_t(count);
  h.check = kMessageCheck;
  h.particle_fields = s.fields_kept;
  if (with_history && st_.keeps_history()) {
    h.slots = st_.history.slots;
    h.real_bytes = std::int32_t(sizeof(Real));
    h.fields = st_.kept;
  }
  return h;
}

template <class Exec, class Real>
MessageHeader ParticleMover<Exec, Real>::pack(const ParticleStore& s, const DeviceArray<Index>& w,
                                                                bool with_history,
                                                                DeviceArray<unsigned char>& out) const {
  const MessageHeader h = message_header(s, Index(w.size()), with_history);
  const MessageLayout at(h);
  out.resize(at.bytes);
  unsigned char* b = out.data();
  int k = 0;
  for_each_particle_field(s, [&](const char*, const auto& a) {
    if (a.size() != 0) gather_into<Exec>(a, w, b + at.particle[k]);  // an optional field not kept is empty
    ++k;
  });
  if (h.slots == 0) return h;
  gather_history_into<Exec>(st_.history.partner, w, h.slots, st_.history.strides, b + at.partner);
  k = 0;
  for_each_history_field(st_.history, [&](const char*, unsigned bit, const auto& a) {
    if (h.fields & bit) gather_history_into<Exec>(a, w, h.slots, st_.history.strides, b + at.history[k]);
    ++k;
  });
  return h;
}

template <class Exec, class Real>
void ParticleMover<Exec, Real>::unpack(ParticleStore& s, const MessageHeader& h,
                                                         const unsigned char* payload, bool as_ghosts) {
  if (!as_ghosts && s.n_ghost != 0) throw std::logic_error("owned particles can only be appended before ghosts");
  if (h.check != kMessageCheck) throw std::runtime_error("a particle message from another rank is corrupt");
  // Owned arrivals must carry exactly this run's history; ghosts carry none.
  const MessageHeader want = message_header(s, Index(h.count), !as_ghosts);
  if (h.particle_fields != want.particle_fields)
    throw std::runtime_error("arriving particles carry the optional fields " + std::to_string(h.particle_fields) +
                             ", this run keeps " + std::to_string(want.particle_fields));
  if (h.slots != want.slots || h.real_bytes != want.real_bytes || h.fields != want.fields)
    throw std::runtime_error("arriving particles carry " + std::to_string(h.slots) + " history slots of fields " +
                             std::to_string(h.fields) + " in " + std::to_string(h.real_bytes) +
                             "-byte reals; this run uses " + std::to_string(want.slots) + " of fields " +
                             std::to_string(want.fields) + " in " + std::to_string(want.real_bytes));
  const MessageLayout at(h);
  const std::size_t first = std::size_t(s.size());
  const Index m = Index(h.count);
  s.resize_arrays(first + std::size_t(m));
  int k = 0;
  for_each_particle_field(s, [&](const char*, auto& a) {
    if (a.size() != 0) scatter_from<Exec>(payload + at.particle[k], a, first, m);
    ++k;
  });
  if (as_ghosts) s.n_ghost += m;
  else s.n_owned += m;
  reserve(s.size());
  if (h.slots == 0) return;
  auto scatter_history = [&](std::size_t offset, auto& a) {
    using T = typename std::remove_reference_t<decltype(a)>::value_type;
    Exec::parallel_for(Index(h.slots) * m, ScatterHistory<T>{reinterpret_cast<const T*>(payload + offset), a.data(),
                                                            st_.history.strides, Index(first), m});
  };
  scatter_history(at.partner, st_.history.partner);
  k = 0;
  for_each_history_field(st_.history, [&](const char*, unsigned bit, auto& a) {
    if (h.fields & bit) scatter_history(at.history[k], a);
    ++k;
  });
}

template <class Exec, class Real>
void ParticleMover<Exec, Real>::keep_owned(ParticleStore& s, const DeviceArray<Index>& order) {
  const Index n = Index(order.size());
  keep_in_order(s, order.data(), n);
  s.n_owned = n;
  s.drop_ghosts();
}

template <class Exec, class Real>
void ParticleMover<Exec, Real>::append(ParticleStore& s, const ParticleRecords& r, bool as_ghosts) {
  if (!as_ghosts && s.n_ghost != 0) throw std::logic_error("owned particles can only be appended before ghosts");
  const std::size_t first = std::size_t(s.size());
  ++s.revision;
  const Index m = Index(r.size());
  for_each_kept_particle_field(s, r, s.fields_kept, [&](const char* name, auto& a, const auto& from) {
    if (from.size() != std::size_t(m))
      throw std::invalid_argument(std::string("arriving particles lack the field ") + name + " this run keeps");
    append_from_host(a, from, first);
  });
  if (as_ghosts) s.n_ghost += m;
  else s.n_owned += m;
  reserve(s.size());
  if (as_ghosts || !st_.keeps_history() || m == 0) return;

  const HostHistory& h = r.history;
  if (h.slots != st_.history.slots)
    throw std::runtime_error("arriving particles carry " + std::to_string(h.slots) + " history slots, this run uses " +
                             std::to_string(st_.history.slots));
  const std::size_t slots = std::size_t(h.slots), count = std::size_t(m);
  // Rows i * slots + k into a packed slot-major block, in the device type.
  auto scatter_rows = [&](const auto& rows, auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    std::vector<T> block(slots * count);
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t k = 0; k < slots; ++k) block[k * count + i] = T(rows[i * slots + k]);
    scatter_history_from_host<Exec>(a, block, h.slots, st_.history.strides, Index(first), st_.staging);
  };
  scatter_rows(h.partner, st_.history.partner);
  for_each_history_field(h, st_.history, [&](const char*, unsigned bit, const auto& rows, auto& a) {
    if (st_.kept & bit) scatter_rows(rows, a);
  });
}

// Selected and gathered on the backend, so only the particles on a wall
// cross to the host: the whole history is some 500 bytes per particle there.
template <class Exec, class Real>
ParticleRecords ParticleMover<Exec, Real>::wall_contact_history(const ParticleStore& s) const {
  ParticleRecords r;
  r.history.slots = st_.history.slots;
  if (!st_.keeps_history() || s.n_owned == 0) return r;
  // Selected into the staging buffer (an index per owned particle); only the
  // m selected are kept apart, so the output holds 4 bytes per particle on a
  // wall beside the run, not 4 per particle.
  DeviceArray<unsigned char>& selected = st_.staging;
  selected.resize_discarding(std::size_t(s.n_owned) * sizeof(Index));
  DeviceArray<unsigned char> selection_storage(Exec::backend);
  const Index m = Exec::select(s.n_owned, TouchesWall{st_.history.partner.data(), st_.history.strides, st_.history.slots},
                               reinterpret_cast<Index*>(selected.data()), selection_storage);
  if (m == 0) return r;
  DeviceArray<Index> which(Exec::backend, std::size_t(m));
  backend_copy(Exec::backend, which.data(), selected.data(), std::size_t(m) * sizeof(Index));
  DeviceArray<unsigned char> block(Exec::backend);
  // Rows i * slots + k of field, widened to the host type of `rows`.
  auto fetch = [&](const auto& field, auto& rows) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    using Host = typename std::decay_t<decltype(rows)>::value_type;
    block.resize_discarding(std::size_t(m) * sizeof(T) * std::size_t(st_.history.slots));
    gather_history_into<Exec>(field, which, st_.history.slots, st_.history.strides, block.data());
    std::vector<T> packed(std::size_t(m) * std::size_t(st_.history.slots));
    backend_copy_to_host(Exec::backend, packed.data(), block.data(), packed.size() * sizeof(T));
    const std::vector<T> device_rows = slot_major_to_rows(packed, st_.history.slots, std::size_t(m));
    rows.resize(device_rows.size());
    for (std::size_t e = 0; e < rows.size(); ++e) rows[e] = Host(device_rows[e]);
  };
  block.resize_discarding(std::size_t(m) * sizeof(ParticleId));
  gather_into<Exec>(s.id, which, block.data());
  r.id.resize(std::size_t(m));
  backend_copy_to_host(Exec::backend, r.id.data(), block.data(), r.id.size() * sizeof(ParticleId));
  fetch(st_.history.partner, r.history.partner);
  for_each_history_field(st_.history, r.history, [&](const char*, unsigned bit, const auto& field, auto& rows) {
    if (st_.kept & bit) fetch(field, rows);
  });
  return r;
}

}  // namespace gs
