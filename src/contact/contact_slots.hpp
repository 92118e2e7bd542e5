#pragma once
// Per-particle contact slots: the spring history of each contact of particle i
// is kept by i itself, keyed by the partner's global id, so no two threads
// ever write the same slot and no atomics are needed.
#include "contact/contact_law.hpp"
#include "core/fault.hpp"

namespace gs {

template <class Real, unsigned Effects>
struct SlotTable {
  ParticleId* partner;
  Vec3<Real>* tangential;
  Vec3<Real>* rolling;
  int slots;
  std::size_t stride;

  static constexpr bool kActive = (Effects & (kFriction | kRollingResistance)) != 0;

  // Slot of the contact (i, partner_id): the existing one, or a free one that
  // starts from zero springs. -1 when every slot is taken.
  GS_HD int find_or_claim(Index i, ParticleId partner_id, unsigned touched) const {
    int free_slot = -1;
    for (int s = 0; s < slots; ++s) {
      const ParticleId p = partner[s * stride + i];
      if (p == partner_id) return s;
      if (free_slot < 0 && p == kNoPartner && !(touched & (1u << s))) free_slot = s;
    }
    if (free_slot >= 0) {
      const std::size_t k = free_slot * stride + i;
      partner[k] = partner_id;
      if constexpr ((Effects & kFriction) != 0) tangential[k] = Vec3<Real>();
      if constexpr ((Effects & kRollingResistance) != 0) rolling[k] = Vec3<Real>();
    }
    return free_slot;
  }

  GS_HD ContactSprings<Real> load(Index i, int s) const {
    ContactSprings<Real> springs;
    const std::size_t k = s * stride + i;
    if constexpr ((Effects & kFriction) != 0) springs.tangential = tangential[k];
    if constexpr ((Effects & kRollingResistance) != 0) springs.rolling = rolling[k];
    return springs;
  }

  GS_HD void store(Index i, int s, const ContactSprings<Real>& springs) const {
    const std::size_t k = s * stride + i;
    if constexpr ((Effects & kFriction) != 0) tangential[k] = springs.tangential;
    if constexpr ((Effects & kRollingResistance) != 0) rolling[k] = springs.rolling;
  }

  // Contacts not seen this step have ended: their slots are freed.
  GS_HD void release_untouched(Index i, unsigned touched) const {
    for (int s = 0; s < slots; ++s)
      if (!(touched & (1u << s))) partner[s * stride + i] = kNoPartner;
  }
};

}  // namespace gs
