#pragma once
// The kept table: at a Verlet list rebuild, before the cell list is sorted,
// each owned particle's touching pair contacts (partner id and springs,
// ascending partner id) are copied out of the detached tables
// (engine/pair_history.hpp: the old list's entries, or a pending row) into
// the kept table (PairHistory::kept), and the detached tables are freed; the
// new list's entries then take their springs from it.
//
// Why: the merge used to read the old list's whole table (an id, a flag and
// the springs of every old entry, 17 bytes in fp32 with friction) beside the
// new one, so a rebuild held two tables at once. The kept table holds only
// the contacts (16 bytes each): a loosening bed touches at a third of its
// entries. Kept before the sort, they stand beside neither the cell list nor
// the sort's buffers.
//
// Bitwise the same springs: an entry that does not touch holds zero springs
// and flag 0 (PairSprings::release), which is what an entry left out of the
// kept table starts from; a pending row's contacts are taken in ascending
// partner id, so each is found by the same merge.
//
// Halved rows: where every partner of the new list is an owned particle (the
// store holds no ghosts: one rank, whose periodic axes take the nearest
// image, not ghosts), a pair's two rows hold
// the same contact, its springs the exact negation of each other's (contact/
// pair_springs.hpp: what the CPU's pairs-once path already stores). Then
// only the side of lower id keeps it, and the other side's new entry takes it
// mirrored from the partner's row: half the kept table (16 bytes per pair
// instead of per side), the same bits. A partner of lower id holds the pair
// in its row whatever it is: its tables (its old list's entries or the row it
// arrived with) hold every contact it touched.
#include <cstddef>
#include <cstdint>

#include "contact/contact_model.hpp"
#include "contact/pair_springs.hpp"
#include "core/bits.hpp"
#include "core/one_lane.hpp"
#include "core/partition_point.hpp"
#include "engine/pair_history.hpp"
#include "neighbor/verlet_list.hpp"

namespace gs {

// The pair contacts of owned particle i in the detached tables, ascending
// partner id: f(source, at, partner) with source kFromCarried (carried entry
// `at`) or kFromPending (pending entry `at`).
struct DetachedContacts {
  DetachedTables tables;
  // Halved rows (above): the owned particles' ids, and only the contacts
  // with a partner of higher id are i's; null: every contact.
  const ParticleId* own_id = nullptr;

  GS_HD bool keeps(Index i, ParticleId partner) const { return own_id == nullptr || partner > own_id[i]; }

  template <class F>
  GS_HD int for_each(Index i, const F& f) const {
    const Index o = tables.origin_of(i);
    int n = 0;
    if (o >= kPendingBase) {
      // A row's pairs as they arrived, in any order; a few, so a selection.
      const Index row = o - kPendingBase;
      const ListOffset first = tables.pending_begin[row], end = tables.pending_begin[row + 1];
      bool any = false;
      ParticleId last = 0;
      for (;;) {
        ListOffset best = end;
        ParticleId p_best = 0;
        for (ListOffset c = first; c < end; ++c) {
          const ParticleId p = tables.pending_partner[c];
          if ((any && p <= last) || !keeps(i, p)) continue;
          if (best == end || p < p_best) best = c, p_best = p;
        }
        if (best == end) return n;
        f(int(kFromPending), std::size_t(best), p_best);
        ++n;
        any = true;
        last = p_best;
      }
    }
    if (o >= 0)
      for (ListOffset c = tables.carried_begin[o]; c < tables.carried_begin[o + 1]; ++c)
        if (tables.carried_touching[c] && keeps(i, static_cast<ParticleId>(tables.carried_partner[c]))) {
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

// One pointer per history field (GS_HISTORY_FIELDS), null where the run
// keeps none: the arrays of a table whose entries a pass copies whole.
template <class Real>
struct FieldArrays {
#define GS_FIELD_POINTER(name, value, bit) value<Real>* name = nullptr;
  GS_HISTORY_FIELDS(GS_FIELD_POINTER)
#undef GS_FIELD_POINTER
};

// to's entry k = from's entry at, each kept field.
template <class Real>
GS_HD GS_INLINE void copy_entry(const FieldArrays<Real>& to, std::size_t k, const FieldArrays<Real>& from,
                                std::size_t at) {
#define GS_COPY_FIELD(name, value, bit) \
  if (to.name) to.name[k] = from.name[at];
  GS_HISTORY_FIELDS(GS_COPY_FIELD)
#undef GS_COPY_FIELD
}

// The same, as seen from the pair's other side: mirrored (contact/contact_model.hpp)
// and each zero made +0, as PairSprings::store leaves it.
template <class Real>
GS_HD GS_INLINE void copy_entry_mirrored(const FieldArrays<Real>& to, std::size_t k, const FieldArrays<Real>& from,
                                         std::size_t at) {
#define GS_COPY_FIELD(name, value, bit) \
  if (to.name) to.name[k] = positive_zeros(mirrored_field<Real>(from.name[at]));
  GS_HISTORY_FIELDS(GS_COPY_FIELD)
#undef GS_COPY_FIELD
}

template <class Real>
GS_HD GS_INLINE void zero_entry(const FieldArrays<Real>& to, std::size_t k) {
#define GS_ZERO_FIELD(name, value, bit) \
  if (to.name) to.name[k] = value<Real>{};
  GS_HISTORY_FIELDS(GS_ZERO_FIELD)
#undef GS_ZERO_FIELD
}

// The kept table's partner ids and fields of owned particle i, at
// kept[begin[i], begin[i + 1]), in one pass. A carried row's touching
// entries are found by the group's vote, each lane placing its own after
// those of the lanes before it; a pending row (an arrival's: rare) is its
// leader's alone.
template <class Real>
struct KeepContacts {
  static constexpr int kMinBlocksPerSM = kRowPassBlocksPerSM;
  DetachedContacts contacts;
  const ListOffset* begin;
  ParticleId* partner;
  FieldArrays<Real> to, carried, pending;
  GS_HD void operator()(Index i) const { in_group(i, OneLane{}); }

  template <class Group>
  GS_HD void in_group(Index i, const Group& g) const {
    const DetachedTables& t = contacts.tables;
    const Index o = t.origin_of(i);
    ListOffset c = begin[i];
    if (o >= kPendingBase) {
      if (g.leader())
        contacts.for_each(i, [&](int, std::size_t at, ParticleId p) {
          partner[c] = p;
          copy_entry(to, c, pending, at);
          ++c;
        });
      return;
    }
    if (o < 0) return;
    const ListOffset end = t.carried_begin[o + 1];
    for (ListOffset first = t.carried_begin[o]; first < end; first += ListOffset(g.size)) {
      const ListOffset e = first + ListOffset(g.rank);
      const bool touching = e < end && t.carried_touching[e] != 0 &&
                            contacts.keeps(i, static_cast<ParticleId>(t.carried_partner[e]));
      const unsigned votes = g.ballot(touching);
      if (touching) {
        const ListOffset at = c + ListOffset(bit_count(votes & ((1u << g.rank) - 1u)));
        partner[at] = static_cast<ParticleId>(t.carried_partner[e]);
        copy_entry(to, at, carried, e);
      }
      c += ListOffset(bit_count(votes));
    }
  }
};

// Where the kept table's arrays lie in its storage: the partner ids,
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

// The new list's entries of owned particle i take their touching flag and
// fields from the kept contact of the same partner, or start from zero where
// there is none; both rows are in ascending partner id, so each lane merges
// its own entries (r, r + size, ...) with the kept row, from where its last
// entry's search ended. In halved rows an entry whose partner has the lower
// id finds the pair in the partner's kept row, by bisection, mirrored.
template <class Real>
struct MergeKept {
  static constexpr int kMinBlocksPerSM = kRowPassBlocksPerSM;
  const ListOffset* begin;  // the new list
  const Index* list;
  const ParticleId* id;
  const ListOffset* kept_begin;
  const ParticleId* kept_partner;
  FieldArrays<Real> kept;
  std::uint8_t* touching;  // the new list's entries
  FieldArrays<Real> to;
  bool halved = false;
  GS_HD void operator()(Index i) const { in_group(i, OneLane{}); }

  template <class Group>
  GS_HD void in_group(Index i, const Group& g) const {
    ListOffset c = kept_begin[i];
    const ListOffset c_end = kept_begin[i + 1];
    const ParticleId own = id[i];
    for (ListOffset k = begin[i] + ListOffset(g.rank); k < begin[i + 1]; k += ListOffset(g.size)) {
      const Index j = list[k];
      const ParticleId partner = id[j];
      if (halved && partner < own) {
        const ListOffset at = find_kept(j, own);
        if (at != kNoEntry) {
          touching[k] = 1;
          copy_entry_mirrored(to, k, kept, at);
        } else {
          touching[k] = 0;
          zero_entry(to, k);
        }
        continue;
      }
      while (c < c_end && kept_partner[c] < partner) ++c;
      if (c < c_end && kept_partner[c] == partner) {
        touching[k] = 1;
        copy_entry(to, k, kept, c);
      } else {
        touching[k] = 0;
        zero_entry(to, k);
      }
    }
  }

  // The entry of particle j's kept row that names `partner`, or kNoEntry.
  GS_HD ListOffset find_kept(Index j, ParticleId partner) const {
    const ListOffset end = kept_begin[j + 1];
    const ListOffset at = partition_point(kept_begin[j], end, [&](ListOffset k) { return kept_partner[k] < partner; });
    return at < end && kept_partner[at] == partner ? at : kNoEntry;
  }
};

}  // namespace gs
