#pragma once
// Per-particle contact slots for the contacts with walls and mesh features
// (`surface_slots` of them): the spring history of each such contact of
// particle i is kept by i itself, keyed by the partner's id (kWallPartnerBase
// + w, mesh_partner_id), so no two threads ever write the same slot and no
// atomics are needed. Particle pairs keep theirs per Verlet list entry
// instead (contact/pair_springs.hpp), where no search and no partner id is
// needed. (The layout of the table is core/history_layout.hpp.)
//
// Only a particle that can touch a wall or a mesh before the next build of
// the neighbour lists has a row of slots (engine/surface_rows.hpp): `row[i]`
// is particle i's row of the table, kNoSurfaceRow where it has none, so a bed
// far from its walls holds 4 bytes per particle instead of a row each.
#include "contact/contact_law.hpp"
#include "core/fault.hpp"
#include "core/history_layout.hpp"

namespace gs {

constexpr int kNoRowSlot = -2;  // find_or_claim for a particle without a row

// Kept: the history fields of the run (HistoryField bits,
// contact/contact_models.hpp history_fields_kept); none: no history at all.
template <class Real, unsigned Kept>
struct SlotTable {
  const Index* row;  // per owned particle: its row of slots, or kNoSurfaceRow
  ParticleId* partner;
#define GS_DECLARE_FIELD(name, value, bit) value<Real>* name;
  GS_HISTORY_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD
  int slots;
  HistoryStrides strides;

  static constexpr bool kActive = Kept != 0;

  // Slot of the contact (i, partner_id): the existing one, or a free one that
  // starts from zero springs. -1 when every slot is taken, kNoRowSlot when
  // particle i has no row.
  GS_HD int find_or_claim(Index i, ParticleId partner_id, unsigned touched) const {
    const Index r = row[i];
    if (r == kNoSurfaceRow) return kNoRowSlot;
    const std::size_t base = std::size_t(r) * strides.particle_stride;
    int free_slot = -1;
    for (int s = 0; s < slots; ++s) {
      const ParticleId p = partner[base + std::size_t(s) * strides.slot_stride];
      if (p == partner_id) return s;
      if (free_slot < 0 && p == kNoPartner && !(touched & (1u << s))) free_slot = s;
    }
    if (free_slot >= 0) {
      const std::size_t k = strides.at(free_slot, std::size_t(r));
      partner[k] = partner_id;
#define GS_CLEAR_FIELD(name, value, bit) \
  if constexpr ((Kept & (bit)) != 0) name[k] = value<Real>{};
      GS_HISTORY_FIELDS(GS_CLEAR_FIELD)
#undef GS_CLEAR_FIELD
    }
    return free_slot;
  }

  // Slot of the existing contact (i, partner_id), or -1.
  GS_HD int find(Index i, ParticleId partner_id) const {
    const Index r = row[i];
    if (r == kNoSurfaceRow) return -1;
    const std::size_t base = std::size_t(r) * strides.particle_stride;
    for (int s = 0; s < slots; ++s)
      if (partner[base + std::size_t(s) * strides.slot_stride] == partner_id) return s;
    return -1;
  }

  // A contact that moved to another feature of the same surface continues:
  // the first slot not yet touched this step whose partner `same_contact`
  // accepts is handed to partner_id with its springs. -1 when there is none.
  template <class SameContact>
  GS_HD int inherit(Index i, ParticleId partner_id, unsigned touched, const SameContact& same_contact) const {
    const Index r = row[i];
    if (r == kNoSurfaceRow) return -1;
    const std::size_t base = std::size_t(r) * strides.particle_stride;
    for (int s = 0; s < slots; ++s) {
      ParticleId& p = partner[base + std::size_t(s) * strides.slot_stride];
      if (p != kNoPartner && !(touched & (1u << s)) && same_contact(p)) {
        p = partner_id;
        return s;
      }
    }
    return -1;
  }

  // (load and store: slot s of a particle that has a row)
  GS_HD ContactState<Real> load(Index i, int s) const {
    ContactState<Real> state;
    const std::size_t k = strides.at(s, std::size_t(row[i]));
#define GS_LOAD_FIELD(name, value, bit) \
  if constexpr ((Kept & (bit)) != 0) state.name = name[k];
    GS_HISTORY_FIELDS(GS_LOAD_FIELD)
#undef GS_LOAD_FIELD
    return state;
  }

  GS_HD void store(Index i, int s, const ContactState<Real>& state) const {
    const std::size_t k = strides.at(s, std::size_t(row[i]));
#define GS_STORE_FIELD(name, value, bit) \
  if constexpr ((Kept & (bit)) != 0) name[k] = state.name;
    GS_HISTORY_FIELDS(GS_STORE_FIELD)
#undef GS_STORE_FIELD
  }

  // Contacts not seen this step have ended: their slots are freed.
  GS_HD void release_untouched(Index i, unsigned touched) const {
    const Index r = row[i];
    if (r == kNoSurfaceRow) return;
    const std::size_t base = std::size_t(r) * strides.particle_stride;
    for (int s = 0; s < slots; ++s)
      if (!(touched & (1u << s))) partner[base + std::size_t(s) * strides.slot_stride] = kNoPartner;
  }
};

}  // namespace gs
