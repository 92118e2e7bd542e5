#pragma once
// Cell list rebuilt every step: particles are sorted by the key (cell, id),
// then each cell's range in the sorted order is recorded. Sorting by id within
// a cell is what makes every particle's contact sum canonical.
//
// The ranges are kept as offsets (cell c holds sorted[cell_begin[c],
// cell_begin[c + 1]), empty cells included), so the cells of one row of the
// grid, consecutive in x, form one contiguous range in `sorted`.
#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "backend/device_array.hpp"
#include "core/partition_point.hpp"
#include "core/types.hpp"
#include "neighbor/cell_grid.hpp"

namespace gs {

struct CellList {
  explicit CellList(Backend b) : sorted(b), cell_begin(b) {}

  CellGrid grid;
  DeviceArray<Index> sorted;      // particle indices in (cell, id) order
  DeviceArray<Index> cell_begin;  // per cell + 1: offsets in `sorted`

  std::size_t bytes() const { return sorted.bytes() + cell_begin.bytes(); }
  // Frees both arrays (the next build sizes them again); the grid stays.
  void discard() noexcept {
    sorted.discard();
    cell_begin.discard();
  }
};

// The pairs a radix sort orders: keys carrying indices, each with a second
// buffer of the same length (the passes alternate between the two). On
// return `keys` and `values` point to the sorted pairs, in either buffer.
// Keys of 32 bits where they fit (a GPU's cells alone, ids), else 64: the
// buffers are a step's largest transient where nothing else is.
template <class Key>
struct SortPairs {
  static_assert(std::is_same_v<Key, std::uint32_t> || std::is_same_v<Key, std::uint64_t>, "32- or 64-bit keys");
  Key* keys;
  Key* keys_alt;
  Index* values;
  Index* values_alt;
  Index n;
  int key_bits;  // the keys' significant low bits
};

// A particle's sort key: its cell above id_bits bits of its id (32), or the
// cell alone (id_bits 0: the stable sort then keeps a cell's particles in
// memory order).
template <class Key>
struct CellKeys {
  const Vec3d* position;
  const ParticleId* id;
  CellGrid grid;
  Key* keys;
  Index* values;
  int id_bits;
  GS_HD void operator()(Index i) const {
    const Key cell = Key(grid.linear(grid.coord(position[i])));
    keys[i] = id_bits == 0 ? cell : Key(cell << id_bits) | Key(id[i]);  // (64-bit keys where id_bits > 0)
    values[i] = i;
  }
};

// Offsets from the particles' side, item k in [0, n]: every cell after the
// cell of particle k - 1, up to the cell of particle k, starts at k. The work
// is O(n + cells) in all, but one item walks a whole empty stretch of cells.
template <class Key>
struct CellBeginsByParticle {
  const Key* keys;
  Index n;
  std::int64_t cells;
  Index* cell_begin;
  int id_bits;  // CellKeys'
  GS_HD void operator()(Index k) const {
    const std::int64_t first = k == 0 ? 0 : std::int64_t(keys[k - 1] >> id_bits) + 1;
    const std::int64_t last = k == n ? cells : std::int64_t(keys[k] >> id_bits);
    for (std::int64_t c = first; c <= last; ++c) cell_begin[c] = k;
  }
};

// Offsets from the cells' side, item c in [0, cells]: a binary search for the
// first particle in cell c or after it. Each item does O(log n) work.
template <class Key>
struct CellBeginsByCell {
  const Key* keys;
  Index n;
  Index* cell_begin;
  int id_bits;  // CellKeys'
  GS_HD void operator()(Index c) const {
    const Key first_key = Key(Key(c) << id_bits);
    cell_begin[c] = partition_point(Index(0), n, [&](Index k) { return keys[k] < first_key; });
  }
};

// The cells next to cell c along one axis (offsets -1, 0, 1 in that order),
// each once: at a face, the cells beyond it are left out, or on a periodic
// axis taken from the other face (an axis of one or two cells has fewer
// distinct neighbours). Returns how many are in `out`.
GS_HD GS_INLINE int neighbour_cells(const CellGrid& grid, int axis, int c, int out[3]) {
  const int n = grid.dims[axis];
  int k = 0;
  for (int d = -1; d <= 1; ++d) {
    int v = c + d;
    if (v < 0 || v >= n) {
      if (!grid.box.wraps(axis)) continue;
      v = v < 0 ? v + n : v - n;
    }
    bool seen = false;
    for (int m = 0; m < k; ++m) seen = seen || out[m] == v;
    if (!seen) out[k++] = v;
  }
  return k;
}

// Contact candidates of a particle from the cell list: every particle in the
// 27 cells around the particle's cell, in a fixed order (dz, dy, dx) and, in
// a cell, by ascending id on the CPU (the list is sorted by (cell, id)), in
// memory order on a GPU (Exec::cell_keys_hold_ids). The cells of a
// row that are consecutive in x are consecutive in the list, so they are
// read as one range, in that same order. The particle itself is among them.
struct CellCandidates {
  CellGrid grid;
  const Index* sorted;      // particle indices by cell (and id on the CPU)
  const Index* cell_begin;  // per cell + 1: cell c is sorted[cell_begin[c], cell_begin[c + 1])

  // visit_run(first, end) for each run of sorted[] that the 27 cells
  // around xi hold: a row of cells consecutive in x is one run (all of them
  // but across a periodic face).
  template <class VisitRun>
  GS_HD GS_INLINE void for_each_run(const Vec3d& xi, VisitRun& visit_run) const {
    const CellCoord c = grid.coord(xi);
    int xs[3], ys[3], zs[3];
    const int nx = neighbour_cells(grid, 0, c.x, xs), ny = neighbour_cells(grid, 1, c.y, ys),
              nz = neighbour_cells(grid, 2, c.z, zs);
    for (int a = 0; a < nz; ++a)
      for (int b = 0; b < ny; ++b) {
        const std::int64_t row = grid.linear(CellCoord{0, ys[b], zs[a]});
        for (int first = 0; first < nx;) {
          int last = first;
          while (last + 1 < nx && xs[last + 1] == xs[last] + 1) ++last;
          visit_run(cell_begin[row + xs[first]], cell_begin[row + xs[last] + 1]);
          first = last + 1;
        }
      }
  }
  template <class Visit>
  GS_HD GS_INLINE void for_each(Index /*i*/, const Vec3d& xi, Visit& visit) const {
    auto each = [&](Index first, Index end) {
      for (Index k = first; k < end; ++k) visit(sorted[k]);
    };
    for_each_run(xi, each);
  }
};

inline int bits_needed(std::uint64_t v) {
  int b = 0;
  while (v > 0) { ++b; v >>= 1; }
  return b;
}

// Where the sort's keys, its second buffers and its own storage go in the
// scratch buffer: offsets of 256-byte aligned parts.
struct SortLayout {
  std::size_t keys = 0, keys_alt = 0, values_alt = 0, storage = 0, total = 0;
  static std::size_t aligned(std::size_t b) { return (b + 255) / 256 * 256; }
  SortLayout(Index n, std::size_t key_bytes, std::size_t storage_bytes) {
    const std::size_t k = aligned(std::size_t(n) * key_bytes), v = aligned(std::size_t(n) * sizeof(Index));
    keys_alt = k;
    values_alt = 2 * k;
    storage = 2 * k + v;
    total = storage + storage_bytes;
  }
};

// Sorts n pairs (keys written by make_keys(p), values) with their second
// buffers and the sort's storage in `scratch`; the sorted values end in
// `values` (`values` is also the pairs' first value buffer), and the sorted
// keys are returned (in `scratch`, valid until its next use).
template <class Exec, class Key, class MakeKeys>
const Key* sort_in_scratch(Index n, int key_bits, Index* values, DeviceArray<unsigned char>& scratch,
                           const MakeKeys& make_keys) {
  const std::size_t storage_bytes = Exec::template sort_storage_bytes<Key>(n, key_bits);
  const SortLayout at(n, sizeof(Key), storage_bytes);
  scratch.resize_discarding(at.total);
  unsigned char* base = scratch.data();
  SortPairs<Key> p{reinterpret_cast<Key*>(base + at.keys), reinterpret_cast<Key*>(base + at.keys_alt), values,
                   reinterpret_cast<Index*>(base + at.values_alt), n, key_bits};
  make_keys(p);
  Exec::sort_pairs(p, base + at.storage, storage_bytes);
  if (p.values != values && n > 0) backend_copy(Exec::backend, values, p.values, std::size_t(n) * sizeof(Index));
  return p.keys;
}

// Bins particles [0, n) into the grid's cells. The keys and the sort's
// second buffers live in `scratch` only during this call (the step's staging
// buffer, which holds nothing between calls: engine/step_state.hpp), so a
// run does not keep the sort's buffers (12 bytes per particle with 32-bit
// keys, 20 with 64) beside the staging buffer it needs anyway.
template <class Exec, class Key>
void build_cells_keyed(CellList& c, const Vec3d* position, const ParticleId* id, Index n, const CellGrid& grid,
                       int id_bits, int key_bits, DeviceArray<unsigned char>& scratch) {
  const Key* keys = sort_in_scratch<Exec, Key>(n, key_bits, c.sorted.data(), scratch, [&](SortPairs<Key>& p) {
    Exec::parallel_for(n, CellKeys<Key>{position, id, grid, p.keys, p.values, id_bits});
  });
  if constexpr (Exec::cell_begins_by_particle)
    Exec::parallel_for(n + 1, CellBeginsByParticle<Key>{keys, n, grid.cell_count(), c.cell_begin.data(), id_bits});
  else
    Exec::parallel_for(Index(grid.cell_count() + 1), CellBeginsByCell<Key>{keys, n, c.cell_begin.data(), id_bits});
}

template <class Exec>
void build_cells(CellList& c, const Vec3d* position, const ParticleId* id, Index n, const CellGrid& grid,
                 DeviceArray<unsigned char>& scratch) {
  c.grid = grid;
  c.sorted.resize_discarding(std::size_t(n));  // both rewritten whole
  c.cell_begin.resize_discarding(std::size_t(grid.cell_count()) + 1);
  const int id_bits = Exec::cell_keys_hold_ids ? 32 : 0;
  // At least one bit: a grid of one cell, keyed by cell alone, still sorts.
  const int key_bits = std::max(1, id_bits + bits_needed(std::uint64_t(grid.cell_count() - 1)));
  // (Keys with ids take 64 bits: a shift by the ids' 32 would overflow 32-bit keys.)
  if (id_bits == 0 && key_bits <= 32)
    build_cells_keyed<Exec, std::uint32_t>(c, position, id, n, grid, id_bits, key_bits, scratch);
  else
    build_cells_keyed<Exec, std::uint64_t>(c, position, id, n, grid, id_bits, key_bits, scratch);
}

}  // namespace gs
