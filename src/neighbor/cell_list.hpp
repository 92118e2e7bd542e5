#pragma once
// Cell list rebuilt every step: particles are sorted by the key (cell, id),
// then each cell's range in the sorted order is recorded. Sorting by id within
// a cell is what makes every particle's contact sum canonical.
//
// The ranges are kept as offsets (cell c holds sorted[cell_begin[c],
// cell_begin[c + 1]), empty cells included), so the cells of one row of the
// grid, consecutive in x, form one contiguous range in `sorted`.
#include <cstdint>

#include "backend/device_array.hpp"
#include "core/types.hpp"
#include "neighbor/cell_grid.hpp"

namespace gs {

struct CellList {
  explicit CellList(Backend b)
      : keys(b), keys_alt(b), sorted(b), sorted_alt(b), cell_begin(b), sort_scratch(b) {}

  CellGrid grid;
  DeviceArray<std::uint64_t> keys, keys_alt;
  DeviceArray<Index> sorted, sorted_alt;
  DeviceArray<Index> cell_begin;  // per cell + 1: offsets in `sorted`
  DeviceArray<unsigned char> sort_scratch;
  int key_bits = 64;

  std::size_t bytes() const {
    return keys.bytes() + keys_alt.bytes() + sorted.bytes() + sorted_alt.bytes() + cell_begin.bytes() +
           sort_scratch.bytes();
  }
};

struct CellKeys {
  const Vec3d* position;
  const ParticleId* id;
  CellGrid grid;
  std::uint64_t* keys;
  Index* sorted;
  GS_HD void operator()(Index i) const {
    keys[i] = (std::uint64_t(grid.linear(grid.coord(position[i]))) << 32) | id[i];
    sorted[i] = i;
  }
};

// Offsets from the particles' side, item k in [0, n]: every cell after the
// cell of particle k - 1, up to the cell of particle k, starts at k. The work
// is O(n + cells) in all, but one item walks a whole empty stretch of cells.
struct CellBeginsByParticle {
  const std::uint64_t* keys;
  Index n;
  std::int64_t cells;
  Index* cell_begin;
  GS_HD void operator()(Index k) const {
    const std::int64_t first = k == 0 ? 0 : std::int64_t(keys[k - 1] >> 32) + 1;
    const std::int64_t last = k == n ? cells : std::int64_t(keys[k] >> 32);
    for (std::int64_t c = first; c <= last; ++c) cell_begin[c] = k;
  }
};

// Offsets from the cells' side, item c in [0, cells]: a binary search for the
// first particle in cell c or after it. Each item does O(log n) work.
struct CellBeginsByCell {
  const std::uint64_t* keys;
  Index n;
  Index* cell_begin;
  GS_HD void operator()(Index c) const {
    const std::uint64_t first_key = std::uint64_t(c) << 32;
    Index lo = 0, hi = n;
    while (lo < hi) {
      const Index mid = lo + (hi - lo) / 2;
      if (keys[mid] < first_key) lo = mid + 1;
      else hi = mid;
    }
    cell_begin[c] = lo;
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
// a cell, by ascending id (the list is sorted by (cell, id)). The cells of a
// row that are consecutive in x are consecutive in the list, so they are
// read as one range, in that same order. The particle itself is among them.
struct CellCandidates {
  CellGrid grid;
  const Index* sorted;      // particle indices in (cell, id) order
  const Index* cell_begin;  // per cell + 1: cell c is sorted[cell_begin[c], cell_begin[c + 1])

  template <class Visit>
  GS_HD GS_INLINE void for_each(Index /*i*/, const Vec3d& xi, Visit& visit) const {
    const CellCoord c = grid.coord(xi);
    int xs[3], ys[3], zs[3];
    const int nx = neighbour_cells(grid, 0, c.x, xs), ny = neighbour_cells(grid, 1, c.y, ys),
              nz = neighbour_cells(grid, 2, c.z, zs);
    for (int a = 0; a < nz; ++a)
      for (int b = 0; b < ny; ++b) {
        const std::int64_t row = grid.linear(CellCoord{0, ys[b], zs[a]});
        // Runs of cells consecutive in x (all of them but across a periodic face).
        for (int first = 0; first < nx;) {
          int last = first;
          while (last + 1 < nx && xs[last + 1] == xs[last] + 1) ++last;
          const Index end = cell_begin[row + xs[last] + 1];
          for (Index k = cell_begin[row + xs[first]]; k < end; ++k) visit(sorted[k]);
          first = last + 1;
        }
      }
  }
};

inline int bits_needed(std::uint64_t v) {
  int b = 0;
  while (v > 0) { ++b; v >>= 1; }
  return b;
}

template <class Exec>
void build_cells(CellList& c, const Vec3d* position, const ParticleId* id, Index n, const CellGrid& grid) {
  c.grid = grid;
  c.keys.resize(n);
  c.keys_alt.resize(n);
  c.sorted.resize(n);
  c.sorted_alt.resize(n);
  c.cell_begin.resize(std::size_t(grid.cell_count()) + 1);
  c.key_bits = 32 + bits_needed(std::uint64_t(grid.cell_count() - 1));
  Exec::parallel_for(n, CellKeys{position, id, grid, c.keys.data(), c.sorted.data()});
  Exec::sort_pairs(c, n);
  if constexpr (Exec::cell_begins_by_particle)
    Exec::parallel_for(n + 1, CellBeginsByParticle{c.keys.data(), n, grid.cell_count(), c.cell_begin.data()});
  else
    Exec::parallel_for(Index(grid.cell_count() + 1), CellBeginsByCell{c.keys.data(), n, c.cell_begin.data()});
}

}  // namespace gs
