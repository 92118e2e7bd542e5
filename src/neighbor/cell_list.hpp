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

// Contact candidates of a particle from the cell list: every particle in the
// 27 cells around the particle's cell, in a fixed order (dz, dy, dx) and, in
// a cell, by ascending id (the list is sorted by (cell, id)). The three cells
// dx = -1, 0, 1 of a row are consecutive in the list, so a row is read as one
// range, in that same order. The particle itself is among them.
struct CellCandidates {
  CellGrid grid;
  const Index* sorted;      // particle indices in (cell, id) order
  const Index* cell_begin;  // per cell + 1: cell c is sorted[cell_begin[c], cell_begin[c + 1])

  template <class Visit>
  GS_HD GS_INLINE void for_each(Index /*i*/, const Vec3d& xi, Visit& visit) const {
    const CellCoord c = grid.coord(xi);
    const int x_first = c.x > 0 ? c.x - 1 : 0;
    const int x_last = c.x + 1 < grid.dims[0] ? c.x + 1 : c.x;
    for (int dz = -1; dz <= 1; ++dz) {
      const int z = c.z + dz;
      if (z < 0 || z >= grid.dims[2]) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        const int y = c.y + dy;
        if (y < 0 || y >= grid.dims[1]) continue;
        const std::int64_t row = grid.linear(CellCoord{0, y, z});
        const Index end = cell_begin[row + x_last + 1];
        for (Index k = cell_begin[row + x_first]; k < end; ++k) visit(sorted[k]);
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
