#pragma once
// The history of particle-particle contacts, one entry per Verlet list entry
// (neighbor/verlet_list.hpp): entry k of particle i holds the springs of the
// pair (i, list[k]), so no partner id is stored and the force kernel reads
// and writes its entry directly, without a search. An entry whose pair does
// not touch holds zero springs and touching = 0 (the contact ended, or has
// not begun); a new contact starts from zero springs as a slot claimed in a
// SlotTable does (contact/contact_slots.hpp, which keeps the contacts with
// walls and mesh features). Only thread i writes i's entries: no atomics.
// The storage and its carry-over across list rebuilds, re-sorts and
// migration: engine/pair_history.hpp.
#include <cstddef>
#include <cstdint>

#include "contact/contact_model.hpp"
#include "core/hd.hpp"

namespace gs {

// Kept: the history fields of the run (HistoryField bits).
template <class Real, unsigned Kept>
struct PairSprings {
  std::uint8_t* touching;  // 1 where the pair touched at the last force computation
#define GS_DECLARE_FIELD(name, value, bit) value<Real>* name;
  GS_HISTORY_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD

  GS_HD ContactState<Real> load(std::size_t k) const {
    ContactState<Real> state;
#define GS_LOAD_FIELD(name, value, bit) \
  if constexpr ((Kept & (bit)) != 0) state.name = name[k];
    GS_HISTORY_FIELDS(GS_LOAD_FIELD)
#undef GS_LOAD_FIELD
    return state;
  }

  // The state of a touching pair.
  GS_HD void store(std::size_t k, const ContactState<Real>& state) const {
    touching[k] = 1;
#define GS_STORE_FIELD(name, value, bit) \
  if constexpr ((Kept & (bit)) != 0) name[k] = state.name;
    GS_HISTORY_FIELDS(GS_STORE_FIELD)
#undef GS_STORE_FIELD
  }

  // A pair that does not touch: its contact, if any, has ended.
  GS_HD void release(std::size_t k) const {
    if (!touching[k]) return;  // zero already
    store(k, ContactState<Real>{});
    touching[k] = 0;
  }
};

}  // namespace gs
