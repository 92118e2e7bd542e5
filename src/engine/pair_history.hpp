#pragma once
// The particle-pair contact history of one rank and how it follows the
// Verlet list (contact/pair_springs.hpp says what an entry holds).
//
// Attached: `current` holds one entry per entry of the list the neighbour
// finder holds (the CSR shares the list's offsets).
// Detached: from the first change of the store after a build (re-sort,
// migration, removal, insertion, ghosts dropped: ParticleStore::observer)
// or at the next build, until that build. The old list's entries are turned
// from store indices into the partners' ids before anything moves, and the
// old list's offsets, ids and entries become the `carried` table, row r for
// the particle that was owned particle r then. Each owned particle's
// `origin` names its row, and moves with the particle (a re-sort or a
// compaction gathers it as any field); particles that arrive from another
// rank or from the host (insertion, restart) bring a row of (partner id,
// springs) as messages and checkpoints hold it (width contact_slots): its
// surface contacts go to the surface table at once, and its pair contacts
// alone, in row order, wait in the `pending` table until the build (a CSR
// table: a restart's rows of 12 or more slots hold a few touching pairs);
// inserted particles have none.
// At the build, before the cell list is sorted, each particle's touching
// contacts are copied from its carried or pending row into the kept table
// (ascending partner id: engine/pair_keep.hpp) and the carried and pending
// tables are freed; then the cell list and the new list are built and
// each particle's new entries (ascending partner id) take their springs from
// its kept contacts (a merge); the rest start from zero.
//
// Contacts with walls and mesh features stay in a small slot table per
// particle (contact/contact_slots.hpp, `surface_slots` of them), which moves
// with its particle as before. A particle's row for messages, checkpoints
// and output (ContactRows) lists its touching pairs by ascending partner id,
// then its surface slots in slot order; a pending row's pairs in the order
// they came.
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "backend/device_array.hpp"
#include "contact/pair_springs.hpp"
#include "core/fault.hpp"
#include "core/history_layout.hpp"
#include "core/one_lane.hpp"
#include "core/particle_fields.hpp"
#include "neighbor/verlet_list.hpp"

namespace gs {

// origin values: a carried row, kPendingBase + a pending row, or none.
constexpr Index kNoOrigin = -1;
constexpr Index kPendingBase = Index(1) << 30;

// One entry per pair: whether it touches, and the history fields the run keeps.
template <class Real>
struct PairEntries {
  DeviceArray<std::uint8_t> touching;
#define GS_DECLARE_FIELD(name, value, bit) DeviceArray<value<Real>> name;
  GS_HISTORY_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD

  explicit PairEntries(Backend b) : touching(b) {
    for_each_history_field(*this, [b](const char*, unsigned, auto& a) { a = std::decay_t<decltype(a)>(b); });
  }
  // n entries of the kept fields, contents undefined.
  void resize_discarding(std::size_t n, unsigned kept) {
    touching.resize_discarding(n);
    for_each_history_field(*this, [&](const char*, unsigned bit, auto& a) {
      if (kept & bit) a.resize_discarding(n);
    });
  }
  void resize(std::size_t n, unsigned kept) {
    touching.resize(n);
    resize_fields(n, kept);
  }
  // The kept fields alone, keeping their first entries (rows whose touching
  // flags go unused: the pending rows).
  void resize_fields(std::size_t n, unsigned kept) {
    for_each_history_field(*this, [&](const char*, unsigned bit, auto& a) {
      if (kept & bit) a.resize(n);
    });
  }
  void reserve_fields(std::size_t n, unsigned kept) {
    for_each_history_field(*this, [&](const char*, unsigned bit, auto& a) {
      if (kept & bit) a.reserve(n);
    });
  }
  void swap(PairEntries& o) {
    touching.swap(o.touching);
    for_each_history_field(*this, o, [](const char*, unsigned, auto& a, auto& b) { a.swap(b); });
  }
  std::size_t bytes() const {
    std::size_t total = touching.bytes();
    for_each_history_field(*this, [&](const char*, unsigned, const auto& a) { total += a.bytes(); });
    return total;
  }
  template <unsigned Kept>
  PairSprings<Real, Kept> view() {
    PairSprings<Real, Kept> v;
    v.touching = touching.data();
#define GS_POINT_AT_FIELD(name, value, bit) v.name = name.data();
    GS_HISTORY_FIELDS(GS_POINT_AT_FIELD)
#undef GS_POINT_AT_FIELD
    return v;
  }
};

// The detached tables as kernels read them: per owned particle its origin
// (a carried row, kPendingBase + a pending row, or none), the carried rows'
// offsets, partner ids and touching flags, and the pending rows' offsets and
// partners.
struct DetachedTables {
  const Index* origin;
  Index n_origin;
  const ListOffset* carried_begin;
  const Index* carried_partner;
  const std::uint8_t* carried_touching;
  const ListOffset* pending_begin;
  const ParticleId* pending_partner;

  GS_HD Index origin_of(Index i) const { return i < n_origin ? origin[i] : kNoOrigin; }
};

template <class Real>
struct PairHistory {
  explicit PairHistory(Backend b)
      : current(b),
        carried_begin(b),
        carried_partner(b),
        carried(b),
        origin(b),
        pending_begin(b),
        pending_partner(b),
        pending(b),
        kept_begin(b),
        kept(b) {}

  bool attached = false;         // current follows the finder's list
  PairEntries<Real> current;     // per list entry
  // Detached (see the top):
  DeviceArray<ListOffset> carried_begin;  // per carried row + 1
  DeviceArray<Index> carried_partner;     // partner ids (as Index bits), ascending in each row
  PairEntries<Real> carried;
  DeviceArray<Index> origin;              // per owned particle (missing at the end: none)
  DeviceArray<ListOffset> pending_begin;    // per pending row + 1 (none before the first arrival)
  DeviceArray<ParticleId> pending_partner;  // the rows' pair contacts: partner ids
  PairEntries<Real> pending;                // their fields (touching unused)
  Index pending_rows = 0;
  // During a build: the kept table's offsets, per owned particle + 1, and
  // its contacts (partner ids and fields as KeptLayout places them:
  // engine/pair_keep.hpp), kept before the cell list is sorted and merged
  // into the new list's entries once it is built.
  DeviceArray<ListOffset> kept_begin;
  DeviceArray<unsigned char> kept;

  // The detached tables freed once their contacts are kept, before the new
  // list is allocated, so that the two are never held at once. (On a GPU a
  // free returns the memory to the device's pool, backend/memory.hpp, which
  // serves the next build's allocations from it without a wait.)
  void drop_detached() {
    carried_begin.discard();
    carried_partner.discard();
    origin.discard();
    pending_begin.discard();
    pending_partner.discard();
    carried.touching.discard();
    pending.touching.discard();
    for_each_history_field(carried, pending, [&](const char*, unsigned, auto& a, auto& b) {
      a.discard();
      b.discard();
    });
    pending_rows = 0;
  }

  DetachedTables detached_tables() const {
    return {origin.data(),           Index(origin.size()), carried_begin.data(),   carried_partner.data(),
            carried.touching.data(), pending_begin.data(), pending_partner.data()};
  }

  std::size_t bytes() const {
    return current.bytes() + carried_begin.bytes() + carried_partner.bytes() + carried.bytes() + origin.bytes() +
           pending_begin.bytes() + pending_partner.bytes() + pending.bytes() + kept_begin.bytes() + kept.bytes();
  }
};

// Lanes per particle of a build's passes over the rows of the pair tables
// on a GPU (Exec::parallel_for_lanes; ListToIds here, engine/pair_keep.hpp):
// lane r takes entries r, r + 8, ... of its particle's row, so a warp's
// reads and writes of the tables are runs of consecutive entries, not one
// row per lane 16-72 bytes apart (docs/PERFORMANCE.md, "A rebuild's copies
// by groups of lanes"). Rows are a few to a few dozen entries.
constexpr int kRowLanes = 8;
// A launch hint, as the force kernel's (the passes need few registers).
constexpr int kRowPassBlocksPerSM = 4;

// The old list's entries of owned particle i, from store indices to ids; on
// a GPU by a group of kRowLanes lanes.
struct ListToIds {
  static constexpr int kMinBlocksPerSM = kRowPassBlocksPerSM;
  const ListOffset* begin;
  Index* list;
  const ParticleId* id;
  GS_HD void operator()(Index i) const { in_group(i, OneLane{}); }
  template <class Group>
  GS_HD void in_group(Index i, const Group& g) const {
    for (ListOffset k = begin[i] + ListOffset(g.rank); k < begin[i + 1]; k += ListOffset(g.size))
      list[k] = static_cast<Index>(id[list[k]]);
  }
};

struct Iota {
  Index* to;
  GS_HD void operator()(Index i) const { to[i] = i; }
};

template <class T>
struct Fill {
  T* to;
  T value;
  GS_HD void operator()(Index i) const { to[i] = value; }
};

// Where a row's entries come from.
enum ContactSource : int { kFromCurrent = 0, kFromCarried = 1, kFromPending = 2, kFromSurface = 3 };

// The contacts of owned particle i as one row of `width` entries: f(r,
// source, at, partner) for entry r < width. Returns how many contacts there
// are (more than width: those beyond are not visited).
struct ContactRows {
  int width;
  bool attached;
  // attached: the list and its entries' flags
  const ListOffset* begin;
  const Index* list;
  const ParticleId* id;
  const std::uint8_t* current_touching;
  DetachedTables detached;
  // walls and mesh features: each particle's row of the surface table
  const Index* surface_row;
  const ParticleId* surface_partner;
  HistoryStrides strides;
  int surface_slots;

  template <class F>
  GS_HD int for_each(Index i, const F& f) const {
    int r = 0;
    auto put = [&](int source, std::size_t at, ParticleId partner) {
      if (r < width) f(r, source, at, partner);
      ++r;
    };
    if (attached) {
      for (ListOffset k = begin[i]; k < begin[i + 1]; ++k)
        if (current_touching[k]) put(kFromCurrent, std::size_t(k), id[list[k]]);
    } else {
      const Index o = detached.origin_of(i);
      if (o >= kPendingBase) {
        const Index row = o - kPendingBase;
        for (ListOffset c = detached.pending_begin[row]; c < detached.pending_begin[row + 1]; ++c)
          put(kFromPending, std::size_t(c), detached.pending_partner[c]);
      } else if (o >= 0)
        for (ListOffset c = detached.carried_begin[o]; c < detached.carried_begin[o + 1]; ++c)
          if (detached.carried_touching[c])
            put(kFromCarried, std::size_t(c), static_cast<ParticleId>(detached.carried_partner[c]));
    }
    const Index row = surface_row[i];
    if (row == kNoSurfaceRow) return r;
    for (int s = 0; s < surface_slots; ++s) {
      const std::size_t at = strides.at(s, std::size_t(row));
      if (surface_partner[at] != kNoPartner) put(kFromSurface, at, surface_partner[at]);
    }
    return r;
  }
};

// Row k of field T, from store index i (engine/row_order.hpp, for_rows), in
// the host's or message's type U: row-major rows of `width` (to[k * width +
// r]) or a packed slot-major block of m (to[r * m + k]). from[source]: the
// field's array of each source.
template <class T, class U>
struct ContactRowValues {
  ContactRows rows;
  const T* from[4];
  U* to;
  Index m;
  bool slot_major;
  GS_HD void operator()(Index k, Index i) const {
    auto at = [&](int r) -> U& {
      return slot_major ? to[std::size_t(r) * std::size_t(m) + std::size_t(k)]
                        : to[std::size_t(k) * std::size_t(rows.width) + std::size_t(r)];
    };
    for (int r = 0; r < rows.width; ++r) at(r) = U{};
    rows.for_each(i, [&](int r, int source, std::size_t e, ParticleId) { at(r) = U(from[source][e]); });
  }
};

// The partner ids of the same rows (kNoPartner where empty); a particle with
// more contacts than the row holds is a fault (contact_slots).
struct ContactRowPartners {
  ContactRows rows;
  ParticleId* to;
  Index m;
  bool slot_major;
  const ParticleId* id;
  Fault* fault;
  GS_HD void operator()(Index k, Index i) const {
    auto at = [&](int r) -> ParticleId& {
      return slot_major ? to[std::size_t(r) * std::size_t(m) + std::size_t(k)]
                        : to[std::size_t(k) * std::size_t(rows.width) + std::size_t(r)];
    };
    for (int r = 0; r < rows.width; ++r) at(r) = kNoPartner;
    const int n = rows.for_each(i, [&](int r, int, std::size_t, ParticleId partner) { at(r) = partner; });
    if (n > rows.width) report_fault(fault, kFaultSlotsExhausted, id[i], -1);
  }
};

// Row k: the contacts of store index i.
struct CountRowContacts {
  ContactRows rows;
  std::uint16_t* count;
  GS_HD void operator()(Index k, Index i) const {
    count[k] = std::uint16_t(rows.for_each(i, [](int, int, std::size_t, ParticleId) {}));
  }
};

// Arrivals [first, first + m) have pending rows [row0, row0 + m).
struct PendingOrigins {
  Index* origin;
  Index first, row0;
  GS_HD void operator()(Index k) const { origin[first + k] = kPendingBase + row0 + k; }
};

// Arriving rows as they come: a packed slot-major block of m rows of
// `width` (entry s of row k at s * m + k), partner ids and each field alike.
struct ArrivingRows {
  const ParticleId* partner;
  int width;
  Index m;
  GS_HD std::size_t at(Index k, int s) const { return std::size_t(s) * std::size_t(m) + std::size_t(k); }
  GS_HD bool pair(std::size_t e) const { return names_particle(partner[e]); }
  GS_HD bool surface(std::size_t e) const { return partner[e] != kNoPartner && !names_particle(partner[e]); }
};

// Row k's pair contacts counted into begin[k + 1], the pending entries
// before the arrivals (`base`) added to the first (item 0 also sets begin[0]
// = base), so that an in-place inclusive scan gives the arrivals' pending
// offsets (PairHistory::pending_begin from row0 on).
struct CountArrivingPairs {
  ArrivingRows rows;
  ListOffset* begin;
  ListOffset base;
  GS_HD void operator()(Index k) const {
    ListOffset n = k == 0 ? base : 0;
    for (int s = 0; s < rows.width; ++s) n += rows.pair(rows.at(k, s)) ? 1 : 0;
    if (k == 0) begin[0] = base;
    begin[k + 1] = n;
  }
};

// Row k's pair contacts of one array (partner ids or a field), in row order,
// into its pending entries from begin[k] on.
template <class T>
struct PairsToPending {
  ArrivingRows rows;
  const T* from;
  T* to;
  const ListOffset* begin;
  GS_HD void operator()(Index k) const {
    ListOffset c = begin[k];
    for (int s = 0; s < rows.width; ++s) {
      const std::size_t e = rows.at(k, s);
      if (rows.pair(e)) to[c++] = from[e];
    }
  }
};

// The surface contacts (walls, mesh features) of arriving row k into the
// surface row of particle first + k, in row order: f(slot, block entry).
struct PendingSurfaces {
  ArrivingRows rows;
  int slots;
  Index first;
  const Index* row;  // the particles' surface rows
  template <class F>
  GS_HD int for_each(Index k, const F& f) const {
    int n = 0;
    for (int s = 0; s < rows.width && n < slots; ++s) {
      const std::size_t e = rows.at(k, s);
      if (rows.surface(e)) f(n++, e);
    }
    return n;
  }
};

// Whether arrival k has surface contacts: begin[k + 1] = 1 or 0 (item 0
// also sets begin[0] = 0), for a scan into new surface rows.
struct CountPendingSurfaces {
  PendingSurfaces rows;
  ListOffset* begin;
  GS_HD void operator()(Index k) const {
    if (k == 0) begin[0] = 0;
    begin[k + 1] = rows.for_each(k, [](int, std::size_t) {}) > 0 ? 1 : 0;
  }
};

// Arrival k's surface row: base + begin[k] where it has surface contacts.
struct PendingSurfaceRows {
  Index* row;
  Index first, base;
  const ListOffset* begin;
  GS_HD void operator()(Index k) const {
    row[first + k] = begin[k + 1] > begin[k] ? base + Index(begin[k]) : kNoSurfaceRow;
  }
};

// Their partner ids, the other slots free.
struct PendingPartnersToSurface {
  PendingSurfaces rows;
  ParticleId* to;
  HistoryStrides strides;
  GS_HD void operator()(Index k) const {
    const Index r = rows.row[rows.first + k];
    if (r == kNoSurfaceRow) return;
    const std::size_t i = std::size_t(r);
    int n = rows.for_each(k, [&](int s, std::size_t e) { to[strides.at(s, i)] = rows.rows.partner[e]; });
    for (; n < rows.slots; ++n) to[strides.at(n, i)] = kNoPartner;
  }
};

// Their values of one field (from: the arriving block of that field).
template <class T>
struct PendingFieldToSurface {
  PendingSurfaces rows;
  const T* from;
  T* to;
  HistoryStrides strides;
  GS_HD void operator()(Index k) const {
    const Index r = rows.row[rows.first + k];
    if (r == kNoSurfaceRow) return;
    const std::size_t i = std::size_t(r);
    rows.for_each(k, [&](int s, std::size_t e) { to[strides.at(s, i)] = from[e]; });
  }
};

// Whether arriving row k holds more surface contacts than `slots`.
struct SurfaceOverflow {
  ArrivingRows rows;
  const ParticleId* id;  // of the arriving particles, at first + k
  int slots;
  Index first;
  Fault* fault;
  GS_HD void operator()(Index k) const {
    int n = 0;
    for (int s = 0; s < rows.width; ++s) n += rows.surface(rows.at(k, s)) ? 1 : 0;
    if (n > slots) report_fault(fault, kFaultSurfaceSlotsExhausted, id[first + k], -1);
  }
};

}  // namespace gs
