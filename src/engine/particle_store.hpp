#pragma once
// All particle state of one rank as a structure of arrays in backend memory,
// one array per field of core/particle_fields.hpp (which says the precision
// of each). Owned particles occupy [0, n_owned); ghost copies of neighbours'
// particles follow in [n_owned, n_owned + n_ghost).
#include <cstdint>
#include <type_traits>

#include "backend/device_array.hpp"
#include "core/history_layout.hpp"
#include "core/particle_fields.hpp"

namespace gs {

template <class Real>
struct ForceArrays {
  DeviceArray<Vec3<Real>> force;   // contact force [N]
  DeviceArray<Vec3<Real>> torque;  // contact torque [N m]
};

// The contact history of walls and mesh features: a table of `capacity`
// rows of `slots` slots, laid out as `strides` says (core/history_layout.hpp;
// the execution policy picks the order), of which [0, rows) are in use, and
// each owned particle's row (`row`, kNoSurfaceRow where it has none:
// engine/surface_rows.hpp). A field the run does not keep stays empty.
template <class Real>
struct ContactHistory {
  int slots = 0;
  std::size_t capacity = 0;
  Index rows = 0;
  bool row_for_every_particle = false;  // RunOptions::surface_row_for_every_particle
  HistoryStrides strides;
  DeviceArray<Index> row;           // per particle
  DeviceArray<ParticleId> partner;  // kNoPartner marks a free slot
#define GS_DECLARE_FIELD(name, value, bit) DeviceArray<value<Real>> name;
  GS_HISTORY_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD

  // Empty arrays in memory of backend b.
  void place_on(Backend b) {
    row = DeviceArray<Index>(b);
    partner = DeviceArray<ParticleId>(b);
    for_each_history_field(*this, [b](const char*, unsigned, auto& a) { a = std::decay_t<decltype(a)>(b); });
  }
};

struct ParticleStore;

// Told before a store's particles are added, removed, reordered or their
// ghosts dropped: what indexes the store by position (the Verlet list's
// pair springs, engine/pair_history.hpp) must read it one last time.
struct StoreObserver {
  virtual void store_changing(const ParticleStore& s) = 0;

 protected:
  ~StoreObserver() = default;
};

struct ParticleStore {
  Backend backend = Backend::cpu;
  Index n_owned = 0;
  Index n_ghost = 0;
  // Raised whenever particles are added, removed or reordered: a neighbour
  // list built at an older revision no longer describes the store.
  std::uint64_t revision = 0;
  // The optional fields this run keeps (ParticleField bits); the others stay empty.
  unsigned fields_kept = 0;
  // Set by the pair history when a list is built on the store (mutable: the
  // build sees a const store); null before.
  mutable StoreObserver* observer = nullptr;

#define GS_DECLARE_FIELD(name, type, kept) DeviceArray<type> name;
  GS_PARTICLE_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD

  Index size() const { return n_owned + n_ghost; }

  // Empty arrays in memory of backend b.
  void place_on(Backend b) {
    backend = b;
    for_each_particle_field(*this, [b](const char*, auto& a) { a = std::decay_t<decltype(a)>(b); });
  }
  // Before particles are added, removed or reordered: the observer reads
  // the store as it is, then the revision moves on.
  void begin_change() {
    if (observer) observer->store_changing(*this);
    ++revision;
  }
  // Sets the length of every array (contents up to min(old, n) are kept).
  void resize_arrays(std::size_t n) {
    begin_change();
    for_each_kept_particle_field(*this, fields_kept, [n](const char*, auto& a) { a.resize(n); });
  }
  void drop_ghosts() {
    n_ghost = 0;
    resize_arrays(std::size_t(n_owned));
  }
  std::size_t bytes() const {
    std::size_t total = 0;
    for_each_particle_field(*this, [&](const char*, const auto& a) { total += a.bytes(); });
    return total;
  }
};

}  // namespace gs
