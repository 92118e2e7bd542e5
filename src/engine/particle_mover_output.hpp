#pragma once
// Out-of-line members of ParticleMover that copy the owned particles to the
// host for output and checkpoints: each field put in the order asked for
// (id order) by a backend kernel and copied once, owned particles only, into
// host arrays that the caller reuses from one output to the next.
#include <algorithm>
#include <type_traits>

namespace gs {

// Row k of `to` from store index i (engine/row_order.hpp, for_rows), in the
// host's type U (fp32 forces widen to fp64 exactly).
template <class T, class U>
struct RowAs {
  const T* from;
  U* to;
  GS_HD void operator()(Index k, Index i) const { to[k] = U(from[i]); }
};

// Host array `out` of n rows of `width` values, written by rows(first, m,
// to): a kernel that writes rows [first, first + m) at `to`. On the CPU the
// kernel writes `out` itself. On a GPU the rows go a chunk at a time through
// the staging array's two halves and the pinned bounce buffer's
// (backend/host_pins.hpp): chunk c is put in order in staging half c % 2 and
// copied to bounce half c % 2, both queued, while the host moves chunk c - 1
// from the other bounce half to its place in `out` (pageable: no array pinned
// whole) on every host thread. Without a bounce buffer (a copy made once)
// each chunk, as large as the rule allows, goes straight to its place.
template <class Exec, class U, class Rows>
void rows_to_host(std::vector<U>& out, Index n, std::size_t width, HostPins& pins, DeviceArray<unsigned char>& staging,
                  const Rows& rows) {
  pins.resize(Exec::backend, out, std::size_t(n) * width);
  if (n == 0 || width == 0) return;
  if constexpr (Exec::backend == Backend::cpu) {
    rows(0, n, out.data());
  } else {
    const std::size_t row_bytes = width * sizeof(U);
    const Index allowed = output_chunk_rows(n, row_bytes, staging.bytes());
    // With a bounce buffer, two halves of the chunk the rule allows: the output holds no more.
    const Index half = std::max<Index>(1, allowed / 2);
    const bool halves = pins.hold_halves(Exec::backend, std::size_t(half) * row_bytes);
    const Index chunk = halves ? half : allowed;
    const std::size_t chunk_bytes = std::size_t(chunk) * row_bytes;
    staging.resize_discarding((halves ? 2 : 1) * chunk_bytes);
    auto staged = [&](int h) { return reinterpret_cast<U*>(staging.data() + std::size_t(h) * chunk_bytes); };
    auto place = [&](Index first) { return out.data() + std::size_t(first) * width; };
    if (!halves) {
      for (Index first = 0; first < n; first += chunk) {
        const Index m = std::min(chunk, n - first);
        rows(first, m, staged(0));
        backend_copy_to_host(Exec::backend, place(first), staged(0), std::size_t(m) * row_bytes);
      }
      return;
    }
    auto bytes_from = [&](Index first) { return std::size_t(std::min(chunk, n - first)) * row_bytes; };
    Index last = -1;  // the chunk queued before (its first row), not yet in its place
    int h = 0;
    for (Index first = 0; first < n; first += chunk, h = 1 - h) {
      rows(first, std::min(chunk, n - first), staged(h));
      pins.fill_half(h, staged(h), bytes_from(first));
      if (last >= 0) host_copy(place(last), pins.filled_half(1 - h), bytes_from(last));
      last = first;
    }
    host_copy(place(last), pins.filled_half(1 - h), bytes_from(last));  // h moved past the last one
  }
}

// Field `a`'s first n values in `order`, as U.
template <class Exec, class T, class U>
void field_to_host(const DeviceArray<T>& a, const RowOrder& order, Index n, std::vector<U>& out, HostPins& pins,
                   DeviceArray<unsigned char>& staging) {
  rows_to_host<Exec>(out, n, 1, pins, staging, [&](Index first, Index m, U* to) {
    for_rows<Exec>(order, first, m, RowAs<T, U>{a.data(), to});
  });
}

template <class Exec, class Real>
void ParticleMover<Exec, Real>::owned_to_host(const ParticleStore& s, const RowOrder& order, ParticleSnapshot& into,
                                              HostPins& pins, bool with_forces) const {
  const Index n = s.n_owned;
  DeviceArray<unsigned char>& staging = st_.staging;
  for_each_particle_field_bit(into, [&](const char*, unsigned bit, auto& field) {
    if (bit != kEveryRun && (s.fields_kept & bit) == 0) field.clear();  // not kept: empty
  });
  for_each_kept_particle_field(s, into, s.fields_kept, [&](const char*, const auto& a, auto& out) {
    field_to_host<Exec>(a, order, n, out, pins, staging);
  });
  if ((s.fields_kept & kAngularVelocities) == 0) {  // nothing spins: its spin is zero
    pins.resize(Exec::backend, into.angular_velocity, std::size_t(n));
    std::fill(into.angular_velocity.begin(), into.angular_velocity.end(), Vec3d{});
  }
  if (with_forces) {
    field_to_host<Exec>(st_.forces.force, order, n, into.force, pins, staging);
    if (st_.torque) {
      field_to_host<Exec>(st_.forces.torque, order, n, into.torque, pins, staging);
    } else {
      pins.resize(Exec::backend, into.torque, std::size_t(n));
      std::fill(into.torque.begin(), into.torque.end(), Vec3d{});  // no effect makes torques
    }
  } else {  // the caller reads neither
    into.force.clear();
    into.torque.clear();
  }
  if (!st_.keeps_history()) {
    into.contacts.clear();
    return;
  }
  const ContactRows rows = pairs_.rows(s);
  rows_to_host<Exec>(into.contacts, n, 1, pins, staging, [&](Index first, Index m, std::uint16_t* to) {
    for_rows<Exec>(order, first, m, CountRowContacts{rows, to});
  });
}

// Each owned particle's row of contacts (engine/pair_history.hpp,
// ContactRows), widened to fp64. Only the fields the run keeps: a checkpoint
// of a frictional bed without rolling resistance carries no rolling zeros.
template <class Exec, class Real>
void ParticleMover<Exec, Real>::history_to_host(const ParticleStore& s, const RowOrder& order, HostHistory& into,
                                                HostPins& pins) const {
  into.slots = st_.row_width;
  into.partner.clear();
  for_each_history_field(into, [](const char*, unsigned, auto& rows) { rows.clear(); });
  if (!st_.keeps_history()) return;
  const Index n = s.n_owned;
  const std::size_t width = std::size_t(st_.row_width);
  const ContactRows rows = pairs_.rows(s);
  rows_to_host<Exec>(into.partner, n, width, pins, st_.staging, [&](Index first, Index m, ParticleId* to) {
    for_rows<Exec>(order, first, m, ContactRowPartners{rows, to, m, false, s.id.data(), st_.fault.data()});
  });
  pairs_.for_each_field_sources(into, [&](int, const auto& from, auto& out) {
    using T = std::remove_const_t<std::remove_pointer_t<std::decay_t<decltype(from[0])>>>;
    using U = typename std::decay_t<decltype(out)>::value_type;
    rows_to_host<Exec>(out, n, width, pins, st_.staging, [&](Index first, Index m, U* to) {
      for_rows<Exec>(order, first, m, ContactRowValues<T, U>{rows, {from[0], from[1], from[2], from[3]}, to, m, false});
    });
  });
}

// Selected and gathered on the backend, so only the particles on a wall
// cross to the host: the whole history is some 500 bytes per particle there.
template <class Exec, class Real>
void ParticleMover<Exec, Real>::wall_contact_history(const ParticleStore& s, ParticleRecords& into,
                                                     HostPins& pins) const {
  {  // only the ids and the history, their arrays kept
    std::vector<ParticleId> id = std::move(into.id);
    HostHistory history = std::move(into.history);
    into = ParticleRecords{};
    into.id = std::move(id);
    into.history = std::move(history);
  }
  HostHistory& h = into.history;
  h.slots = st_.row_width;
  const bool any = st_.keeps_history() && s.n_owned > 0;
  // Selected in store order into the staging buffer (an index per owned
  // particle), then the m selected put in id order by a sort of their own
  // (id, index) pairs: the output holds no order of all the particles, and
  // beside the run 4 bytes per particle and some 16 per particle on a wall.
  Index m = 0;
  DeviceArray<Index> which(Exec::backend);
  if (any) {
    st_.staging.resize_discarding(std::size_t(s.n_owned) * sizeof(Index));
    Index* selected = reinterpret_cast<Index*>(st_.staging.data());
    DeviceArray<unsigned char> scratch(Exec::backend);
    const TouchesWall touches{st_.history.row.data(), st_.history.partner.data(), st_.history.strides, st_.history.slots};
    m = Exec::select(s.n_owned, touches, selected, scratch);
    which.resize(std::size_t(m));
    sort_by_id<Exec>(s.id.data(), selected, m, which.data(), scratch);
  }
  const std::size_t width = std::size_t(std::max(0, h.slots));
  rows_to_host<Exec>(into.id, m, 1, pins, st_.staging, [&](Index first, Index k, ParticleId* to) {
    for_rows<Exec>(RowOrder::gather(which.data()), first, k, RowAs<ParticleId, ParticleId>{s.id.data(), to});
  });
  if (!st_.keeps_history()) {
    h.partner.clear();
    for_each_history_field(h, [](const char*, unsigned, auto& rows) { rows.clear(); });
    return;
  }
  // Each particle's row (engine/pair_history.hpp), widened to the host type.
  const ContactRows rows = pairs_.rows(s);
  rows_to_host<Exec>(h.partner, m, width, pins, st_.staging, [&](Index first, Index k, ParticleId* to) {
    for_rows<Exec>(RowOrder::gather(which.data()), first, k,
                   ContactRowPartners{rows, to, k, false, s.id.data(), st_.fault.data()});
  });
  for_each_history_field(h, [](const char*, unsigned, auto& rows) { rows.clear(); });
  pairs_.for_each_field_sources(h, [&](int, const auto& from, auto& out) {
    using T = std::remove_const_t<std::remove_pointer_t<std::decay_t<decltype(from[0])>>>;
    using U = typename std::decay_t<decltype(out)>::value_type;
    rows_to_host<Exec>(out, m, width, pins, st_.staging, [&](Index first, Index k, U* to) {
      for_rows<Exec>(RowOrder::gather(which.data()), first, k,
                     ContactRowValues<T, U>{rows, {from[0], from[1], from[2], from[3]}, to, k, false});
    });
  });
}

}  // namespace gs
