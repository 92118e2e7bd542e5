#pragma once
// The kept table: at a Verlet list rebuild, once the cell list is built and
// before the new list is, each owned particle's touching pair contacts
// (partner id and springs, ascending partner id) are copied out of the
// detached tables (engine/pair_history.hpp: the old list's entries, or a
// pending row) into the step's staging buffer, and the detached tables are
// freed; the new list's entries then take their springs from it.
//
// Why: the merge used to read the old list's whole table (an id, a flag and
// the springs of every old entry, 17 bytes in fp32 with friction) beside the
// new one, so a rebuild held two tables at once. The kept table holds only
// the contacts (16 bytes each), and in the staging buffer, which a rebuilding
// run holds anyway: a loosening bed touches at a third of its entries.
//
// Bitwise the same springs: an entry that does not touch holds zero springs
// and flag 0 (PairSprings::release), which is what an entry left out of the
// kept table starts from; a pending row's contacts are taken in ascending
// partner id, so each is found by the same merge.
#include <cstddef>
#include <cstdint>

#include "engine/pair_history.hpp"

namespace gs {

// The pair contacts of owned particle i in the detached tables, ascending
// partner id: f(source, at, partner) with source kFromCarried (carried entry
// `at`) or kFromPending (pending entry `at`). Surface contacts of a pending
// row (already in the slot table) and empty entries are left out.
struct DetachedContacts {
  DetachedTables tables;
  int width;

  template <class F>
  GS_HD int for_each(Index i, const F& f) const {
    const Index o = tables.origin_of(i);
    int n = 0;
    if (o >= kPendingBase) {
      // A row as it arrived: its entries in any order; a dozen, so a selection.
      const std::size_t row = std::size_t(o - kPendingBase) * std::size_t(width);
      bool any = false;
      ParticleId last = 0;
      for (;;) {
        int best = -1;
        ParticleId p_best = 0;
        for (int s = 0; s < width; ++s) {
          const ParticleId p = tables.pending_partner[row + std::size_t(s)];
          if (p == kNoPartner || p >= kMeshPartnerBase || (any && p <= last)) continue;
          if (best < 0 || p < p_best) best = s, p_best = p;
        }
        if (best < 0) return n;
        f(int(kFromPending), row + std::size_t(best), p_best);
        ++n;
        any = true;
        last = p_best;
      }
    }
    if (o >= 0)
      for (ListOffset c = tables.carried_begin[o]; c < tables.carried_begin[o + 1]; ++c)
        if (tables.carried_touching[c]) {
          f(int(kFromCarried), std::size_t(c), static_cast<ParticleId>(tables.carried_partner[c]));
          ++n;
        }
    return n;
  }
};

// Counts owned particle i's contacts into begin[i + 1] (begin[0] = 0), for
// the scan that turns them into the kept table's offsets.
struct CountKept {
  DetachedContacts contacts;
  ListOffset* begin;
  GS_HD void operator()(Index i) const {
    begin[i + 1] = ListOffset(contacts.for_each(i, [](int, std::size_t, ParticleId) {}));
    if (i == 0) begin[0] = 0;
  }
};

// Their partner ids at kept[begin[i], begin[i + 1]).
struct KeepPartners {
  DetachedContacts contacts;
  const ListOffset* begin;
  ParticleId* to;
  GS_HD void operator()(Index i) const {
    ListOffset c = begin[i];
    contacts.for_each(i, [&](int, std::size_t, ParticleId partner) { to[c++] = partner; });
  }
};

// Their values of one history field.
template <class T>
struct KeepField {
  DetachedContacts contacts;
  const ListOffset* begin;
  const T* carried;
  const T* pending;
  T* to;
  GS_HD void operator()(Index i) const {
    ListOffset c = begin[i];
    contacts.for_each(i, [&](int source, std::size_t at, ParticleId) {
      to[c++] = source == kFromCarried ? carried[at] : pending[at];
    });
  }
};

// Where the kept table's arrays lie in the staging buffer: the partner ids,
// then each kept history field (GS_HISTORY_FIELDS order), 256-byte aligned.
struct KeptLayout {
  static constexpr int kFields = 3;
  std::size_t partner = 0, field[kFields] = {}, total = 0;

  template <class Real>
  static KeptLayout of(std::size_t contacts, unsigned kept) {
    auto aligned = [](std::size_t b) { return (b + 255) / 256 * 256; };
    KeptLayout at;
    std::size_t end = aligned(contacts * sizeof(ParticleId));
    int f = 0;
#define GS_PLACE_FIELD(name, value, bit)                   \
  if (kept & (bit)) {                                      \
    at.field[f] = end;                                     \
    end += aligned(contacts * sizeof(value<Real>));        \
  }                                                        \
  ++f;
    GS_HISTORY_FIELDS(GS_PLACE_FIELD)
#undef GS_PLACE_FIELD
    at.total = end;
    return at;
  }
};

// The kept entry of each new list entry of owned particle i: f(k, at), at
// the kept entry of the same partner, or -1 (none: zero springs). Both are
// in ascending partner id: a merge.
struct KeptSources {
  const ListOffset* begin;  // the new list
  const Index* list;
  const ParticleId* id;
  const ListOffset* kept_begin;
  const ParticleId* kept_partner;
  template <class F>
  GS_HD void for_each(Index i, const F& f) const {
    ListOffset c = kept_begin[i];
    const ListOffset c_end = kept_begin[i + 1];
    for (ListOffset k = begin[i]; k < begin[i + 1]; ++k) {
      const ParticleId partner = id[list[k]];
      while (c < c_end && kept_partner[c] < partner) ++c;
      f(k, c < c_end && kept_partner[c] == partner ? std::int64_t(c) : std::int64_t(-1));
    }
  }
};

template <class T>
struct MergeKeptField {
  KeptSources sources;
  const T* kept;
  T* to;
  GS_HD void operator()(Index i) const {
    sources.for_each(i, [&](ListOffset k, std::int64_t at) { to[k] = at >= 0 ? kept[at] : T{}; });
  }
};

struct MergeKeptTouching {
  KeptSources sources;
  std::uint8_t* to;
  GS_HD void operator()(Index i) const {
    sources.for_each(i, [&](ListOffset k, std::int64_t at) { to[k] = at >= 0 ? std::uint8_t(1) : std::uint8_t(0); });
  }
};

}  // namespace gs
