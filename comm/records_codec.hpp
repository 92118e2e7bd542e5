#pragma once
// ParticleRecords to bytes and back, for the wire (migration, ghosts, gathers).
#include "comm/transport.hpp"
#include "core/particle_records.hpp"

namespace gs {

void encode_records(const ParticleRecords& r, Bytes& out);
ParticleRecords decode_records(const Bytes& in);
// Appends `more` to `into` (both with, or both without, history).
void append_records(ParticleRecords& into, const ParticleRecords& more);

}  // namespace gs
