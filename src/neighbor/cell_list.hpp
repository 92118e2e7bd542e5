#pragma once
// Cell list rebuilt every step: particles are sorted by the key (cell, id),
// then each cell's range in the sorted order is recorded. Sorting by id within
// a cell is what makes every particle's contact sum canonical.
#include <cstdint>

#include "backend/device_array.hpp"
#include "core/types.hpp"
#include "neighbor/cell_grid.hpp"

namespace gs {

struct CellList {
  explicit CellList(Backend b)
      : keys(b), keys_alt(b), sorted(b), sorted_alt(b), cell_begin(b), cell_end(b), sort_scratch(b) {}

  CellGrid grid;
  DeviceArray<std::uint64_t> keys, keys_alt;
  DeviceArray<Index> sorted, sorted_alt;
  DeviceArray<Index> cell_begin, cell_end;
  DeviceArray<unsigned char> sort_scratch;
  int key_bits = 64;

  std::size_t bytes() const {
    return keys.bytes() + keys_alt.bytes() + sorted.bytes() + sorted_alt.bytes() + cell_begin.bytes() +
           cell_end.bytes() + sort_scratch.bytes();
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

struct CellRanges {
  const std::uint64_t* keys;
  Index n;
  Index* cell_begin;
  Index* cell_end;
  GS_HD void operator()(Index k) const {
    const std::uint64_t cell = keys[k] >> 32;
    if (k == 0 || (keys[k - 1] >> 32) != cell) cell_begin[cell] = k;
    if (k == n - 1 || (keys[k + 1] >> 32) != cell) cell_end[cell] = k + 1;
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
  c.cell_begin.resize(std::size_t(grid.cell_count()));
  c.cell_end.resize(std::size_t(grid.cell_count()));
  c.key_bits = 32 + bits_needed(std::uint64_t(grid.cell_count() - 1));
  Exec::parallel_for(n, CellKeys{position, id, grid, c.keys.data(), c.sorted.data()});
  Exec::sort_pairs(c, n);
  c.cell_begin.zero();
  c.cell_end.zero();
  Exec::parallel_for(n, CellRanges{c.keys.data(), n, c.cell_begin.data(), c.cell_end.data()});
}

}  // namespace gs
