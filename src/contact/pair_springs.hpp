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
#include "core/vec3.hpp"

namespace gs {

// x with a zero made +0 (-0 + +0 is +0 when rounding to nearest; any other x
// is left as it is). add_rounded: never folded away or fused.
template <class Real>
GS_HD GS_INLINE Real positive_zeros(Real x) {
  return add_rounded(x, Real(0));
}
template <class Real>
GS_HD GS_INLINE Vec3<Real> positive_zeros(const Vec3<Real>& v) {
  return add_rounded(v, Vec3<Real>());
}

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

  // The state of a touching pair, each zero stored as +0: the two spheres
  // of a pair compute springs that are exact negations of each other but
  // for the sign of a zero (x - x is +0 from either side), so with zeros
  // made +0 the partner's entry has the same bits whether the partner
  // computed it or took it mirrored from this one (ForceKernel::pair_once).
  GS_HD void store(std::size_t k, const ContactState<Real>& state) const {
    touching[k] = 1;
#define GS_STORE_FIELD(name, value, bit) \
  if constexpr ((Kept & (bit)) != 0) name[k] = positive_zeros(state.name);
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
