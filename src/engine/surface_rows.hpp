#pragma once
// Rows of surface slots (contact/contact_slots.hpp) only for the particles
// that can touch a wall or a mesh before the next build of the neighbour
// lists. At each build an owned particle gets a row when
//  * it holds a wall or mesh contact (a slot in use), or
//  * a triangle is in its near list (walls/mesh_near.hpp), or
//  * an active wall, posed as at the build, is within its reach
//    (wall_within_reach with the skin, walls/wall_geometry.hpp).
// Why that is enough until the next build: a contact later means the
// surface within the particle's radius then; since the build the particle
// has moved at most half the skin (the Verlet list's rule) and every point of
// a wall or mesh near it at most half the skin (WallDrift, MeshDrift: a build
// is due before either would), so at the build the surface was within the
// radius plus the skin. A contact the rule missed would be a defect, which
// the force kernel reports (kFaultSurfaceUnforeseen) instead of starting its
// springs afresh.
//
// The rows follow the particles' order and carry their slots over, so the
// table and the springs are the same whatever the order of the threads. A
// bed in a box keeps a row for its outer layers only: 4 bytes a particle
// (the row's index) instead of a row of 16 bytes a slot for every one.
#include <cstdint>

#include "backend/device_array.hpp"
#include "contact/contact_slots.hpp"
#include "core/particle_fields.hpp"
#include "engine/pair_history.hpp"
#include "engine/particle_store.hpp"
#include "walls/mesh_near.hpp"
#include "walls/wall_geometry.hpp"

namespace gs {

// Whether owned particle i needs a row: begin[i + 1] = 1 or 0 (item 0 also
// sets begin[0] = 0), for a scan of the counts into the rows.
struct SurfaceNeed {
  const Index* row;  // the rows as they are (kNoSurfaceRow where none)
  const ParticleId* partner;
  HistoryStrides strides;
  int slots;
  const Vec3d* position;
  const float* radius;
  const Wall* walls;
  int n_walls;
  MeshNearView near;
  double skin;
  bool every_particle;  // a row for every particle (a check of the rule: the same bits)
  ListOffset* begin;

  GS_HD void operator()(Index i) const {
    if (i == 0) begin[0] = 0;
    begin[i + 1] = needs(i) ? 1 : 0;
  }
  GS_HD bool needs(Index i) const {
    if (every_particle) return true;
    const Index r = row[i];
    if (r != kNoSurfaceRow)
      for (int s = 0; s < slots; ++s)
        if (partner[strides.at(s, std::size_t(r))] != kNoPartner) return true;
    if (near.begin && near.begin[i + 1] > near.begin[i]) return true;
    // The slack of the mesh's near lists, against rounding.
    const double reach = skin * (1 + kMeshNearSlack);
    for (int w = 0; w < n_walls; ++w)
      if (wall_within_reach(walls[w], position[i], double(radius[i]) * (1 + kMeshNearSlack), reach)) return true;
    return false;
  }
};

// The new row begin[i] of particle i (where begin[i + 1] > begin[i]) takes
// its old row's slots of one array (free ones, `empty`, where it had none).
template <class T>
struct MoveSurfaceRow {
  const Index* row;  // the old rows
  const ListOffset* begin;
  const T* from;
  HistoryStrides from_strides;
  T* to;
  HistoryStrides to_strides;
  int slots;
  T empty;
  GS_HD void operator()(Index i) const {
    if (begin[i + 1] == begin[i]) return;
    const Index old = row[i];
    const std::size_t r = std::size_t(begin[i]);
    for (int s = 0; s < slots; ++s)
      to[to_strides.at(s, r)] = old == kNoSurfaceRow ? empty : from[from_strides.at(s, std::size_t(old))];
  }
};

// After every array has moved: each particle's new row, or none.
struct SetSurfaceRow {
  Index* row;
  const ListOffset* begin;
  GS_HD void operator()(Index i) const { row[i] = begin[i + 1] > begin[i] ? Index(begin[i]) : kNoSurfaceRow; }
};

// A table's capacity for `rows` rows: room for those of the particles that
// arrive before the next build.
inline std::size_t surface_capacity(std::size_t rows) { return rows + rows / 4 + 16; }

// Row i of a table in the layout `fresh`: row i of `old` for rows below
// `keep`, `empty` beyond (free slots).
template <class T>
struct RelayoutRow {
  const T* from;
  T* to;
  HistoryStrides old, fresh;
  Index keep;
  int slots;
  T empty;
  GS_HD void operator()(Index i) const {
    const std::size_t p = std::size_t(i);
    for (int s = 0; s < slots; ++s) to[fresh.at(s, p)] = i < keep ? from[old.at(s, p)] : empty;
  }
};

// f(a, empty) for the table's partner ids and each history field the run
// keeps (`kept`) of h, with the value of a free slot.
template <class Real, class F>
void for_each_surface_array(ContactHistory<Real>& h, unsigned kept, F&& f) {
  f(h.partner, kNoPartner);
  for_each_history_field(h, [&](const char*, unsigned bit, auto& a) {
    if (kept & bit) f(a, typename std::decay_t<decltype(a)>::value_type{});
  });
}

// h's table grown to `capacity` rows in the layout of Exec, rows [0, h.rows)
// as they were and the others free (laid out anew: a slot-major table's
// strides are its capacity).
template <class Exec, class Real>
void grow_surface_table(ContactHistory<Real>& h, unsigned kept, std::size_t capacity) {
  const HistoryStrides fresh = HistoryStrides::of(Exec::history_order, h.slots, capacity);
  for_each_surface_array(h, kept, [&](auto& a, auto empty) {
    using T = decltype(empty);
    DeviceArray<T> grown(Exec::backend, std::size_t(h.slots) * capacity);
    Exec::parallel_for(Index(capacity), RelayoutRow<T>{a.data(), grown.data(), h.strides, fresh, h.rows, h.slots, empty});
    a = std::move(grown);
  });
  h.capacity = capacity;
  h.strides = fresh;
}

// Gives rows to the owned particles [0, n) that need them (`need`, whose
// table and `begin` this sets), in their order, moving their slots into a
// new table one array at a time, each old array freed once it has moved.
// `offsets`: scratch for n + 1 offsets; `scan_scratch`: the scan's.
template <class Exec, class Real>
void assign_surface_rows(ContactHistory<Real>& h, unsigned kept, Index n, SurfaceNeed need,
                         DeviceArray<unsigned char>& offsets,
                         DeviceArray<unsigned char>& scan_scratch) {
  offsets.resize_discarding((std::size_t(n) + 1) * sizeof(ListOffset));
  ListOffset* begin = reinterpret_cast<ListOffset*>(offsets.data());
  need.row = h.row.data();
  need.partner = h.partner.data();
  need.strides = h.strides;
  need.slots = h.slots;
  need.every_particle = h.row_for_every_particle;
  need.begin = begin;
  Exec::parallel_for(n, need);
  const Index rows = n == 0 ? 0 : Index(Exec::scan_counts(begin, n, scan_scratch, nullptr));  // at most n
  const std::size_t capacity = surface_capacity(std::size_t(rows));
  const HistoryStrides fresh = HistoryStrides::of(Exec::history_order, h.slots, capacity);
  const HistoryStrides old = h.strides;
  for_each_surface_array(h, kept, [&](auto& a, auto empty) {
    using T = decltype(empty);
    DeviceArray<T> to(Exec::backend, std::size_t(h.slots) * capacity);
    if (n > 0)
      Exec::parallel_for(n, MoveSurfaceRow<T>{h.row.data(), begin, a.data(), old, to.data(), fresh, h.slots, empty});
    a = std::move(to);
  });
  if (n > 0) Exec::parallel_for(n, SetSurfaceRow{h.row.data(), begin});
  h.rows = rows;
  h.capacity = capacity;
  h.strides = fresh;
}

}  // namespace gs
