#pragma once
// Out-of-line members of ParticleMover that refresh ghosts between rebuilds
// of the halo: the fields of engine/ghost_forward.hpp, gathered from the
// owned particles a rebuild selected, scattered over the ghosts it made. No
// array changes size, so the store's revision (and a neighbour list built on
// it) stays valid.
#include <stdexcept>

#include "engine/ghost_forward.hpp"

namespace gs {

template <class Exec, class Real>
void ParticleMover<Exec, Real>::pack_forward(const ParticleStore& s, const DeviceArray<Index>& w,
                                             unsigned char* out) const {
  std::size_t at = 0;
#define GS_PACK_FIELD(name, bit)                                                    \
  if (forwards(bit, s.fields_kept)) {                                               \
    gather_into<Exec>(s.name, w, out + at);                                         \
    at += w.size() * sizeof(decltype(ParticleStore::name)::value_type);             \
  }
  GS_FORWARD_FIELDS(GS_PACK_FIELD)
#undef GS_PACK_FIELD
}

template <class Exec, class Real>
void ParticleMover<Exec, Real>::unpack_forward(ParticleStore& s, const unsigned char* payload, Index first,
                                               Index count) {
  if (first < s.n_owned || first + count > s.size())
    throw std::logic_error("a forward message does not fit the ghosts of the last rebuild");
  std::size_t at = 0;
#define GS_UNPACK_FIELD(name, bit)                                                  \
  if (forwards(bit, s.fields_kept)) {                                               \
    scatter_from<Exec>(payload + at, s.name, std::size_t(first), count);            \
    at += std::size_t(count) * sizeof(decltype(ParticleStore::name)::value_type);   \
  }
  GS_FORWARD_FIELDS(GS_UNPACK_FIELD)
#undef GS_UNPACK_FIELD
}

}  // namespace gs
