#pragma once
// One message of particles between ranks, packed by backend kernels into one
// buffer in backend memory, so that moving it costs one copy (or one NCCL
// send) instead of one per field. The header travels on the host; the payload
// holds each field for all particles in turn, every field 8-byte aligned: the
// particle fields of core/particle_fields.hpp in their order, then the
// history (slot-major: entry s * count + i): partners, then each history
// field the run keeps, in the force precision.
#include <array>
#include <cstddef>
#include <cstdint>

#include "engine/particle_store.hpp"

namespace gs {

struct MessageHeader {
  std::uint64_t count = 0;     // particles
  std::int32_t slots = 0;      // history slots per particle; 0: no history carried
  std::int32_t real_bytes = 0;  // bytes of the history's reals (sizeof(Real)); 0: no history fields
  std::uint32_t fields = 0;    // the history fields carried (HistoryField bits)
  std::uint32_t particle_fields = 0;  // the optional particle fields carried (ParticleField bits)
  std::uint32_t check = 0;     // kMessageCheck: a header that is not one is refused
};
constexpr std::uint32_t kMessageCheck = 0x67734d32u;  // "gsM2"

#define GS_COUNT_FIELD(...) +1
constexpr int kParticleFieldCount = 0 GS_PARTICLE_FIELDS(GS_COUNT_FIELD);
constexpr int kHistoryFieldCount = 0 GS_HISTORY_FIELDS(GS_COUNT_FIELD);
#undef GS_COUNT_FIELD

// Byte offsets of each part of a payload, fields in declaration order.
struct MessageLayout {
  std::array<std::size_t, kParticleFieldCount> particle{};
  std::size_t partner = 0;                            // meaningful only when history is carried
  std::array<std::size_t, kHistoryFieldCount> history{};  // meaningful only for the fields carried
  std::size_t bytes = 0;                              // the whole payload

  explicit MessageLayout(const MessageHeader& h) {
    const std::size_t m = h.count, slots = std::size_t(h.slots);
    std::size_t at = 0;
    auto field = [&](std::size_t each) {
      const std::size_t here = at;
      at += (each * m + 7) / 8 * 8;
      return here;
    };
    int k = 0;
#define GS_LAY_OUT_FIELD(name, type, bit) \
  particle[k++] = field((bit) == kEveryRun || (h.particle_fields & (bit)) != 0 ? sizeof(type) : 0);
    GS_PARTICLE_FIELDS(GS_LAY_OUT_FIELD)
#undef GS_LAY_OUT_FIELD
    partner = field(slots * sizeof(ParticleId));
    k = 0;
    const bool wide = h.real_bytes == int(sizeof(double));
#define GS_LAY_OUT_FIELD(name, value, bit) \
  history[k++] = field((h.fields & (bit)) ? slots * (wide ? sizeof(value<double>) : sizeof(value<float>)) : 0);
    GS_HISTORY_FIELDS(GS_LAY_OUT_FIELD)
#undef GS_LAY_OUT_FIELD
    bytes = at;
  }
};

}  // namespace gs
