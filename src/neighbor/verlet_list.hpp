#pragma once
// Verlet list, on every backend: for each owned particle, the particles
// within r_i + r_j + skin when the list was built, found through the cell
// list (whose cells are then at least a largest diameter plus the skin) and
// kept in ascending id. It stays valid until some particle has moved more
// than half the skin since the build: only then can a pair outside the list
// have come into contact.
//
// Why ascending id: a particle's contact forces are summed in its list's
// order, so that order must not depend on when the list was built (a rank
// rebuilds it with its halo, when a particle on any rank has moved half the
// skin; a single rank when one of its own has), nor
// on where the particles were then. Ordered by the partners' global ids, the
// sum is the same for any build schedule, any number of ranks and either
// backend.
//
// Why on the GPU too: a dense bed's 27 cells hold about 31 candidates per
// particle, of which about six touch it; scanning them every step in fp64
// costs more than reading a short list of 4-byte indices (six entries per
// sphere in a touching lattice at skin 0.1 diameters), rebuilt only when a
// particle has moved half the skin. Its memory: 4 bytes per entry, 4 per
// particle of offsets and 12 of reference position (fp32: see MovedBeyond;
// docs/PERFORMANCE.md).
// The GPU builds it in two passes over the cells (count; a scan turns the
// counts into offsets; fill and sort each particle's entries in place:
// ListCountKernel, ListFillKernel); only the total comes back to the host,
// to size the list. Its staleness is one flag the device sets and the host
// reads after the step's kick-drift (CudaExec::any): one wait for the device
// per step, a few microseconds against the milliseconds of a large bed's step.
// Ranks skip it: the halo's vote has measured the same moves.
#include <cmath>
#include <cstdint>
#include <vector>

#include "backend/device_array.hpp"
#include "core/fault.hpp"
#include "core/types.hpp"
#include "core/vec3.hpp"
#include "neighbor/cell_list.hpp"

namespace gs {

// Offsets into the list: unsigned 32-bit, so a list of up to 2^32 - 1
// entries (4e8 spheres of ten neighbours) costs 4 bytes per particle, not 8.
// A build that would hold more is refused (OffsetsWrapped).
using ListOffset = std::uint32_t;

// Contact candidates of particle i from the list, in ascending id.
struct ListCandidates {
  const ListOffset* begin;  // per owned particle + 1: i's entries are list[begin[i], begin[i + 1])
  const Index* list;        // store indices of the neighbours
  template <class Visit>
  GS_HD GS_INLINE void for_each(Index i, const Vec3d& /*xi*/, Visit& visit) const {
    for (ListOffset k = begin[i]; k < begin[i + 1]; ++k) visit(list[k]);
  }
};

struct VerletList {
  explicit VerletList(Backend b) : begin(b), list(b), reference(b), scan_scratch(b) {}

  DeviceArray<ListOffset> begin;
  DeviceArray<Index> list;
  DeviceArray<Vec3f> reference;  // owned particles' positions at the build, rounded to fp32
  PeriodicBox box;               // the grid's at the build: moves are measured to the nearest image
  std::vector<std::vector<Index>> parts;  // per thread, while building (CPU)
  DeviceArray<unsigned char> scan_scratch;  // the count scan's (GPU), sized at its first use
  double skin = 0;
  Index n_owned = 0, n_total = 0;  // the store's layout at the build
  bool valid = false;

  ListCandidates candidates() const { return {begin.data(), list.data()}; }
  std::size_t bytes() const { return begin.bytes() + list.bytes() + reference.bytes() + scan_scratch.bytes(); }
};

// Whether j (not i) lies within r_i + r_j + skin of x_i (its nearest image).
struct WithinSkin {
  const Vec3d* position;
  const float* radius;
  double skin;
  PeriodicBox box;
  GS_HD bool operator()(Index i, Index j, const Vec3d& xi) const {
    if (j == i) return false;
    const double reach = double(radius[i]) + double(radius[j]) + skin;
    return norm2(box.separation(xi, position[j])) < reach * reach;
  }
};

// Orders a particle's neighbours out[0, n) by ascending id. Insertion sort: a
// dozen entries, mostly in order already (a row of cells comes sorted by id).
GS_HD GS_INLINE void sort_by_id(Index* out, Index n, const ParticleId* id) {
  for (Index a = 1; a < n; ++a) {
    const Index j = out[a];
    Index b = a;
    for (; b > 0 && id[out[b - 1]] > id[j]; --b) out[b] = out[b - 1];
    out[b] = j;
  }
}

// The reference positions: fp32 roundings of the positions at the build.
struct RoundReference {
  const Vec3d* position;
  Vec3f* reference;
  GS_HD void operator()(Index i) const { reference[i] = Vec3f(position[i]); }
};

// Whether owned particle i may have moved more than `limit` since the build
// (a particle wrapped across a periodic face has moved by its nearest image).
// Why fp32 references suffice: rounding to nearest moves a coordinate c by at
// most 2^-24 |c|, so the position at the build lies within
// 2^-24 (|r.x| + |r.y| + |r.z|) of its reference r; that much (doubled, for
// the fp64 arithmetic of the test itself) is taken off the limit, so the
// test can only answer "moved" early, never late. A metre from the origin
// the margin is 0.36 um, against half a skin of 50 um for 1 mm spheres.
struct MovedBeyond {
  const Vec3d* position;
  const Vec3f* reference;
  double limit;
  PeriodicBox box;
  GS_HD bool operator()(Index i) const {
    const Vec3f r = reference[i];
    const double rounding = 0x1p-23 * (std::fabs(double(r.x)) + std::fabs(double(r.y)) + std::fabs(double(r.z))) +
                            0x1p-126;  // subnormal roundings: below the smallest normal fp32
    const double reach = limit - rounding;
    return !(reach > 0) || norm2(box.separation(position[i], Vec3d(r))) > reach * reach;
  }
};

// Counts particle i's neighbours into count[i + 1] (count[0] = 0): the GPU's
// first pass, before the scan that turns the counts into offsets.
struct ListCountKernel {
  CellCandidates cells;
  WithinSkin near;
  ListOffset* count;
  GS_HD void operator()(Index i) const {
    const Vec3d xi = near.position[i];
    ListOffset n = 0;
    auto tally = [&](Index j) { n += near(i, j, xi) ? 1 : 0; };
    cells.for_each(i, xi, tally);
    count[i + 1] = n;
    if (i == 0) count[0] = 0;
  }
};

// Writes particle i's neighbours to list[begin[i], begin[i + 1]) and orders
// them by ascending id: the GPU's second pass, over the same cells.
struct ListFillKernel {
  CellCandidates cells;
  WithinSkin near;
  const ParticleId* id;
  const ListOffset* begin;
  Index* list;
  GS_HD void operator()(Index i) const {
    const Vec3d xi = near.position[i];
    Index* out = list + begin[i];
    Index n = 0;
    auto append = [&](Index j) {
      if (near(i, j, xi)) out[n++] = j;
    };
    cells.for_each(i, xi, append);
    sort_by_id(out, n, id);
  }
};

// Whether the scan of the counts into offsets wrapped past 2^32 (a list too
// long for 32-bit offsets): each count is below 2^32, so a running sum that
// wrapped is smaller than the one before it somewhere.
struct OffsetsWrapped {
  const ListOffset* begin;
  GS_HD bool operator()(Index i) const { return begin[i + 1] < begin[i]; }
};

// Builds the list of the n_owned first particles against all n_total of the
// cell list `cells` (owned and ghosts). Exec::fill_verlet_list finds the
// neighbours, in the backend's memory.
template <class Exec>
void build_verlet_list(VerletList& v, const CellList& cells, const Vec3d* position, const float* radius,
                       const ParticleId* id, Index n_owned, Index n_total, double skin) {
  Exec::fill_verlet_list(v, CellCandidates{cells.grid, cells.sorted.data(), cells.cell_begin.data()},
                         WithinSkin{position, radius, skin, cells.grid.box}, id, n_owned);
  v.reference.resize(std::size_t(n_owned));
  Exec::parallel_for(n_owned, RoundReference{position, v.reference.data()});
  v.skin = skin;
  v.box = cells.grid.box;
  v.n_owned = n_owned;
  v.n_total = n_total;
  v.valid = true;
}

// Whether the list no longer covers every contact of the store.
template <class Exec>
bool verlet_list_stale(const VerletList& v, const Vec3d* position, Index n_owned, Index n_total) {
  if (!v.valid || v.n_owned != n_owned || v.n_total != n_total) return true;
  return Exec::any(n_owned, MovedBeyond{position, v.reference.data(), 0.5 * v.skin, v.box});
}

}  // namespace gs
