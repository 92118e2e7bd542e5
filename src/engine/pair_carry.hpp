#pragma once
// PairCarry: the particle-pair history (engine/pair_history.hpp) carried
// across what changes the store and the Verlet list, on an execution policy:
// detached before the store changes or the list is replaced, its contacts
// kept before the cell list is sorted (engine/pair_keep.hpp),
// merged into the entries of each new list, and read as per-particle rows
// (messages, checkpoints, output) while attached or detached.
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "engine/gather.hpp"
#include "engine/neighbour_finder.hpp"
#include "engine/pair_keep.hpp"
#include "engine/step_state.hpp"
#include "engine/surface_rows.hpp"

namespace gs {

// Whether a build's kept rows are halved (engine/pair_keep.hpp): every
// partner of the new list is owned, the store holding no ghosts.
inline bool halved_rows(const ParticleStore& s) { return s.size() == s.n_owned; }

template <class Exec, class Real>
class PairCarry final : public StoreObserver, public ListFollower {
 public:
  PairCarry(StepState<Real>& state, NeighbourFinder<Exec>& finder) : st_(state), finder_(finder) {
    finder_.follow(this);
  }
  PairCarry(const PairCarry&) = delete;
  PairCarry& operator=(const PairCarry&) = delete;

  void store_changing(const ParticleStore& s) override { detach(s); }
  void list_replacing(const ParticleStore& s) override { detach(s); }
  void list_building(const ParticleStore& s) override;
  void list_built(const ParticleStore& s) override;
  // A touching flag and the kept fields per entry (0 without history).
  std::size_t entry_bytes() const override {
    if (!st_.keeps_history()) return 0;
    std::size_t bytes = sizeof(std::uint8_t);
    for_each_history_field(st_.pairs.current, [&](const char*, unsigned bit, const auto& a) {
      if (st_.kept & bit) bytes += sizeof(typename std::decay_t<decltype(a)>::value_type);
    });
    return bytes;
  }

  // Detached: every owned particle [0, n) has an origin (none where it had not).
  void ensure_origin(Index n) {
    PairHistory<Real>& h = st_.pairs;
    const Index had = Index(h.origin.size());
    if (had >= n) return;
    h.origin.resize(std::size_t(n));
    Exec::parallel_for(n - had, Fill<Index>{h.origin.data() + had, kNoOrigin});
  }
  // Owned particles order[0, n) become [0, n) (after the store began to change).
  void permute(const Index* order, Index n, DeviceArray<unsigned char>& scratch) {
    if (!st_.keeps_history()) return;
    ensure_origin(n);
    PairHistory<Real>& h = st_.pairs;
    scratch.resize_discarding(std::size_t(n) * sizeof(Index));
    Index* tmp = reinterpret_cast<Index*>(scratch.data());
    Exec::parallel_for(n, Gather<Index>{h.origin.data(), tmp, order});
    h.origin.resize(std::size_t(n));
    backend_copy(Exec::backend, h.origin.data(), tmp, std::size_t(n) * sizeof(Index));
  }
  // Room for the rows of owned particles [first, first + m), holding
  // `pairs` pair contacts, arriving in pieces (a restart's:
  // ParticleMover::arrive_from_host), so that the pending table and the
  // origins grow once, not at every piece with their old and new storage
  // held at once.
  void reserve_arrivals(Index first, Index m, std::size_t pairs) {
    if (!st_.keeps_history() || m == 0) return;
    PairHistory<Real>& h = st_.pairs;
    h.pending_begin.reserve(std::size_t(h.pending_rows) + std::size_t(m) + 1);
    h.pending_partner.reserve(h.pending_partner.size() + pairs);
    h.pending.reserve_fields(h.pending_partner.size() + pairs, st_.kept);
    h.origin.reserve(std::size_t(first) + std::size_t(m));
  }
  // m arriving owned particles at [first, first + m), with rows given as
  // packed slot-major blocks in backend memory: partner ids, and each kept
  // field (fields[k] in GS_HISTORY_FIELDS order; null where not kept). Their
  // surface contacts go to the surface table, their pair contacts to the
  // pending table.
  void arrive(Index first, Index m, const ParticleId* partner, const void* const* fields, const ParticleId* id);
  // The rows' view of store s.
  ContactRows rows(const ParticleStore& s) const;
  // f(index, from, out.name) for each kept history field `name`: its index
  // in GS_HISTORY_FIELDS, from[source] its array in each ContactSource
  // (ContactRowValues), and the field of the same name of `out` (host rows,
  // or anything with the history fields' names).
  template <class Out, class F>
  void for_each_field_sources(Out& out, F&& f) const {
    const PairHistory<Real>& h = st_.pairs;
    int index = 0;
#define GS_FIELD_SOURCES(name, value, bit)                                                             \
  if (st_.kept & (bit)) {                                                                              \
    const value<Real>* from[4] = {h.current.name.data(), h.carried.name.data(), h.pending.name.data(), \
                                  st_.history.name.data()};                                            \
    f(index, from, out.name);                                                                          \
  }                                                                                                    \
  ++index;
    GS_HISTORY_FIELDS(GS_FIELD_SOURCES)
#undef GS_FIELD_SOURCES
  }

 private:
  void detach(const ParticleStore& s);
  // The kept fields' arrays of a table, null where the run keeps none.
  FieldArrays<Real> field_arrays(PairEntries<Real>& e) const {
    FieldArrays<Real> a;
#define GS_POINT_AT_FIELD(name, value, bit) \
  if (st_.kept & (bit)) a.name = e.name.data();
    GS_HISTORY_FIELDS(GS_POINT_AT_FIELD)
#undef GS_POINT_AT_FIELD
    return a;
  }
  // The same of the kept table at `base` (kept_).
  FieldArrays<Real> kept_fields(unsigned char* base) const {
    FieldArrays<Real> a;
    int f = 0;
#define GS_POINT_AT_FIELD(name, value, bit)                                          \
  if (st_.kept & (bit)) a.name = reinterpret_cast<value<Real>*>(base + kept_.field[f]); \
  ++f;
    GS_HISTORY_FIELDS(GS_POINT_AT_FIELD)
#undef GS_POINT_AT_FIELD
    return a;
  }
  StepState<Real>& st_;
  NeighbourFinder<Exec>& finder_;
  KeptLayout kept_;  // the kept table's layout, from list_building to list_built
  DeviceArray<ListOffset> arrival_rows_{Exec::backend};  // arrive's scan into new surface rows
};

// The list still describes the store: its entries become the partners' ids
// and, with the entries' springs, the carried table.
template <class Exec, class Real>
void PairCarry<Exec, Real>::detach(const ParticleStore& s) {
  PairHistory<Real>& h = st_.pairs;
  if (!h.attached) return;
  if (!finder_.list_valid(s)) throw std::logic_error("the store changed behind the pair history's back");
  h.attached = false;
  VerletList& v = finder_.verlet();
  Exec::parallel_for_lanes(v.n_owned, kRowLanes, ListToIds{v.begin.data(), v.list.data(), s.id.data()});
  h.carried_begin.swap(v.begin);
  h.carried_partner.swap(v.list);
  h.carried.swap(h.current);
  h.origin.resize(std::size_t(v.n_owned));
  Exec::parallel_for(v.n_owned, Iota{h.origin.data()});
  v.valid = false;
}

// Detached, before the cell list is sorted: each owned particle's contacts
// go to the kept table, and the detached tables are freed before the cell
// list, the new list and its entries are allocated, so the old and the new
// tables are never held at once.
template <class Exec, class Real>
void PairCarry<Exec, Real>::list_building(const ParticleStore& s) {
  if (!st_.keeps_history()) return;
  PairHistory<Real>& h = st_.pairs;
  if (h.attached) throw std::logic_error("the pair history was not detached before the list's build");
  const Index n = s.n_owned;
  const DetachedContacts contacts{h.detached_tables(), halved_rows(s) ? s.id.data() : nullptr};
  // The contacts are among the old list's entries and the pending rows' (so
  // the scan needs no check of its own for wrapping past 32-bit offsets).
  const std::uint64_t bound = std::uint64_t(h.carried_partner.size()) + std::uint64_t(h.pending_partner.size());
  if (bound > std::numeric_limits<ListOffset>::max())
    throw std::runtime_error("the pair history kept across a list rebuild would hold 2^32 entries or more");
  h.kept_begin.resize_discarding(std::size_t(n) + 1);
  if (n == 0) h.kept_begin.zero();
  Exec::parallel_for(n, CountKept{contacts, h.kept_begin.data()});
  const ListOffset total = Exec::scan_counts(h.kept_begin.data(), n, finder_.verlet().scan_scratch, nullptr);
  kept_ = KeptLayout::of<Real>(total, st_.kept);
  h.kept.resize_discarding(kept_.total);
  unsigned char* base = h.kept.data();
  ParticleId* kept_partner = reinterpret_cast<ParticleId*>(base + kept_.partner);
  Exec::parallel_for_lanes(n, kRowLanes,
                           KeepContacts<Real>{contacts, h.kept_begin.data(), kept_partner, kept_fields(base),
                                              field_arrays(h.carried), field_arrays(h.pending)});
  h.drop_detached();
}

// The new list's entries take their springs from the kept table.
template <class Exec, class Real>
void PairCarry<Exec, Real>::list_built(const ParticleStore& s) {
  if (!st_.keeps_history()) return;
  s.observer = this;
  PairHistory<Real>& h = st_.pairs;
  const VerletList& v = finder_.verlet();
  h.current.resize_discarding(v.list.size(), st_.kept);
  unsigned char* base = h.kept.data();
  const ParticleId* kept_partner = reinterpret_cast<const ParticleId*>(base + kept_.partner);
  Exec::parallel_for_lanes(v.n_owned, kRowLanes,
                           MergeKept<Real>{v.begin.data(), v.list.data(), s.id.data(), h.kept_begin.data(), kept_partner,
                                           kept_fields(base), h.current.touching.data(), field_arrays(h.current),
                                           halved_rows(s)});
  h.kept_begin.discard();
  h.kept.discard();
  h.attached = true;
}

template <class Exec, class Real>
void PairCarry<Exec, Real>::arrive(Index first, Index m, const ParticleId* partner, const void* const* fields,
                                   const ParticleId* id) {
  if (!st_.keeps_history() || m == 0) return;
  PairHistory<Real>& h = st_.pairs;
  if (h.attached) throw std::logic_error("particles arrived without a change of the store");
  ensure_origin(first + m);
  const ArrivingRows arriving{partner, st_.row_width, m};
  // Pending rows [row0, row0 + m): their pair contacts after those pending.
  const Index row0 = h.pending_rows;
  h.pending_rows += m;
  h.pending_begin.resize(std::size_t(h.pending_rows) + 1);
  ListOffset* begin = h.pending_begin.data() + row0;
  Exec::parallel_for(m, CountArrivingPairs{arriving, begin, ListOffset(h.pending_partner.size())});
  const std::size_t entries = Exec::scan_counts(begin, m, finder_.verlet().scan_scratch, "the pending contact rows");
  h.pending_partner.resize(entries);
  h.pending.resize_fields(entries, st_.kept);
  Exec::parallel_for(m, PairsToPending<ParticleId>{arriving, partner, h.pending_partner.data(), begin});
  int f = 0;
  for_each_history_field(h.pending, [&](const char*, unsigned bit, auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if ((st_.kept & bit) && fields[f])
      Exec::parallel_for(m, PairsToPending<T>{arriving, static_cast<const T*>(fields[f]), a.data(), begin});
    ++f;
  });
  Exec::parallel_for(m, PendingOrigins{h.origin.data(), first, row0});
  ContactHistory<Real>& surface = st_.history;
  Exec::parallel_for(m, SurfaceOverflow{arriving, id, surface.slots, first, st_.fault.data()});
  // Rows at the table's end for the arrivals with surface contacts, the
  // others none (the next build gives each particle its row anew:
  // engine/surface_rows.hpp); the particles' rows reach first + m (reserve).
  const PendingSurfaces surfaces{arriving, surface.slots, first, surface.row.data()};
  arrival_rows_.resize_discarding(std::size_t(m) + 1);
  Exec::parallel_for(m, CountPendingSurfaces{surfaces, arrival_rows_.data()});
  const Index added = Index(Exec::scan_counts(arrival_rows_.data(), m, finder_.verlet().scan_scratch, nullptr));
  const std::size_t needed = std::size_t(surface.rows) + std::size_t(added);
  if (needed > surface.capacity) grow_surface_table<Exec>(surface, st_.kept, surface_capacity(needed));
  Exec::parallel_for(m, PendingSurfaceRows{surface.row.data(), first, surface.rows, arrival_rows_.data()});
  surface.rows += added;
  Exec::parallel_for(m, PendingPartnersToSurface{surfaces, surface.partner.data(), surface.strides});
  f = 0;
  for_each_history_field(surface, [&](const char*, unsigned bit, auto& to) {
    using T = typename std::decay_t<decltype(to)>::value_type;
    if ((st_.kept & bit) && fields[f])
      Exec::parallel_for(m, PendingFieldToSurface<T>{surfaces, static_cast<const T*>(fields[f]), to.data(),
                                                     surface.strides});
    ++f;
  });
}

template <class Exec, class Real>
ContactRows PairCarry<Exec, Real>::rows(const ParticleStore& s) const {
  const PairHistory<Real>& h = st_.pairs;
  const VerletList& v = finder_.verlet();
  const ContactHistory<Real>& surface = st_.history;
  ContactRows r{};
  r.width = st_.row_width;
  r.attached = h.attached;
  r.begin = v.begin.data();
  r.list = v.list.data();
  r.id = s.id.data();
  r.current_touching = h.current.touching.data();
  r.detached = h.detached_tables();
  r.surface_row = surface.row.data();
  r.surface_partner = surface.partner.data();
  r.strides = surface.strides;
  r.surface_slots = surface.slots;
  return r;
}

}  // namespace gs
