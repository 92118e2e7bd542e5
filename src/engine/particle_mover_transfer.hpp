#pragma once
// Out-of-line members of ParticleMover that move particles between ranks
// and from the host: gather into packed buffers, compact, append.
#include <stdexcept>
#include <string>
#include <type_traits>

#include "engine/particle_message.hpp"

namespace gs {

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
    h.slots = st_.row_width;
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
  // Each particle's row of contacts (engine/pair_history.hpp), slot-major.
  const Index m = Index(w.size());
  const ContactRows rows = pairs_.rows(s);
  const RowOrder which = RowOrder::gather(w.data());
  for_rows<Exec>(which, 0, m, ContactRowPartners{rows, reinterpret_cast<ParticleId*>(b + at.partner), m, true,
                                                 s.id.data(), st_.fault.data()});
  pairs_.for_each_field_sources(st_.history, [&](int index, const auto& from, const auto&) {
    using T = std::remove_const_t<std::remove_pointer_t<std::decay_t<decltype(from[0])>>>;
    for_rows<Exec>(which, 0, m, ContactRowValues<T, T>{rows, {from[0], from[1], from[2], from[3]},
                                                       reinterpret_cast<T*>(b + at.history[std::size_t(index)]), m,
                                                       true});
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
  // The rows wait for the next list build (engine/pair_carry.hpp).
  const void* fields[kHistoryFieldCount] = {};
  k = 0;
  for_each_history_field(st_.history, [&](const char*, unsigned bit, auto&) {
    if (h.fields & bit) fields[k] = payload + at.history[std::size_t(k)];
    ++k;
  });
  pairs_.arrive(Index(first), m, reinterpret_cast<const ParticleId*>(payload + at.partner), fields, s.id.data());
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
  if (h.slots != st_.row_width)
    throw std::runtime_error("arriving particles carry " + std::to_string(h.slots) + " history slots, this run uses " +
                             std::to_string(st_.row_width));
  if (h.partner.size() != std::size_t(m) * std::size_t(h.slots))
    throw std::invalid_argument("arriving particles carry " + std::to_string(h.partner.size()) +
                                " history entries, not one row each");
  arrive_from_host(s, Index(first), h);
}

}  // namespace gs
