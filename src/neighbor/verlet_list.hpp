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
// rebuilds it with its halo, when a particle on any rank may have moved half
// the skin; a single rank when one of its own may have), nor
// on where the particles were then. Ordered by the partners' global ids, the
// sum is the same for any build schedule, any number of ranks and either
// backend.
//
// Why the pairs' springs live here: entry k of particle i also names where
// the contact history of the pair (i, list[k]) is kept (one entry of the
// same index: contact/pair_springs.hpp), so the force kernel needs no search
// and no partner id is stored; across a rebuild the springs are carried over
// by partner id (engine/pair_history.hpp), before the old list is replaced.
//
// Why on the GPU too: a dense bed's 27 cells hold about 31 candidates per
// particle, of which about six touch it; scanning them every step in fp64
// costs more than reading a short list of 4-byte indices (six entries per
// sphere in a touching lattice at skin 0.1 diameters), rebuilt only when a
// particle has moved half the skin. Its memory: 4 bytes per entry, 4 per
// particle of offsets and 12 of reference position (fp32: see distance_from_reference;
// docs/PERFORMANCE.md).
// The GPU builds it in two passes over the cells (count; a scan turns the
// counts into offsets; fill and sort each particle's entries in place:
// ListPass); only the total comes back to the host, to size the list. Where
// a build may hold rows of a fixed width per particle (staged_list_width),
// one pass over the cells writes each particle's neighbours into its row
// while it counts them, and after the scan the rows are copied into place
// (ListPlace); only a particle with more neighbours than the row holds
// passes over its cells again.
//
// Its staleness is read one step late, so that the host never waits for
// the device inside a step (ListWatch below; docs/DESIGN.md, "The step's
// data flow"); with ranks it is each rank's part of the halo's vote
// (RankExchange::halo_stale), whose rebuild rebuilds the list.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "backend/device_array.hpp"
#include "core/bits.hpp"
#include "core/fault.hpp"
#include "core/one_lane.hpp"
#include "core/partition_point.hpp"
#include "core/types.hpp"
#include "core/vec3.hpp"
#include "neighbor/cell_list.hpp"

namespace gs {

// Offsets into the list: unsigned 32-bit, so a list of up to 2^32 - 1
// entries (4e8 spheres of ten neighbours) costs 4 bytes per particle, not 8.
// A build that would hold more is refused (OffsetsWrapped).
using ListOffset = std::uint32_t;
// An entry that names no entry (VerletList::reverse of a ghost partner).
constexpr ListOffset kNoEntry = ~ListOffset(0);

// Contact candidates of particle i from the list, in ascending id: visit(j,
// k) with k the entry's index (where the pair's springs live:
// contact/pair_springs.hpp), or visit(j) for a visitor that takes only j.
struct ListCandidates {
  const ListOffset* begin;  // per owned particle + 1: i's entries are list[begin[i], begin[i + 1])
  const Index* list;        // store indices of the neighbours
  template <class Visit>
  GS_HD GS_INLINE void for_each(Index i, const Vec3d& /*xi*/, Visit& visit) const {
    for (ListOffset k = begin[i]; k < begin[i + 1]; ++k) {
      if constexpr (std::is_invocable_v<Visit&, Index, ListOffset>) visit(list[k], k);
      else visit(list[k]);
    }
  }
};

struct VerletList {
  explicit VerletList(Backend b) : begin(b), list(b), reference(b), reverse(b), scan_scratch(b) {}

  DeviceArray<ListOffset> begin;
  DeviceArray<Index> list;
  DeviceArray<Vec3f> reference;  // owned particles' positions at the build, rounded to fp32
  // Per entry (i, j): the entry of j's row that names i, or kNoEntry where j
  // is a ghost (no row). Kept where each pair is computed once for both of
  // its spheres (Exec::pairs_once: the CPU); empty elsewhere.
  DeviceArray<ListOffset> reverse;
  PeriodicBox box;               // the grid's at the build: moves are measured to the nearest image
  std::vector<std::vector<Index>> parts;  // per thread, while building (CPU)
  DeviceArray<unsigned char> scan_scratch;  // the count scan's (GPU), sized at its first use
  double skin = 0;
  int lanes_setting = 1;  // GPU lanes per particle of the build's passes: force_lanes_setting() (0: by size)
  int staged_width = 0;   // GPU: the rows' width of a build in one pass (staged_list_width); 0: two passes
  Index n_owned = 0, n_total = 0;  // the store's layout at the build
  bool valid = false;

  ListCandidates candidates() const { return {begin.data(), list.data()}; }
  std::size_t bytes() const {
    return begin.bytes() + list.bytes() + reference.bytes() + reverse.bytes() + scan_scratch.bytes();
  }
};

// Whether owned particle i's list names a ghost (a store index past the
// owned particles), for want_ghost true; whether it names none, for false.
struct ListNamesGhost {
  const ListOffset* begin;
  const Index* list;
  Index n_owned;
  bool want_ghost;
  GS_HD bool operator()(Index i) const {
    bool ghost = false;
    for (ListOffset k = begin[i]; k < begin[i + 1] && !ghost; ++k) ghost = list[k] >= n_owned;
    return ghost == want_ghost;
  }
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
// dozen entries (on the CPU mostly in order already: a row of cells comes
// sorted by id there).
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

// An upper bound of how far a particle at x is from where the list saw it,
// given its fp32 reference r (a particle wrapped across a periodic face has
// moved by its nearest image). Why fp32 references suffice: rounding to
// nearest moves a coordinate c by at most 2^-24 |c|, so the position at the
// build lies within 2^-24 (|r.x| + |r.y| + |r.z|) of r; that much (doubled,
// for the fp64 arithmetic of the test itself) is added to the distance to r,
// so a move can only be found early, never late. A metre from the origin the
// addition is 0.36 um, against half a skin of 50 um for 1 mm spheres.
template <class T>
GS_HD GS_INLINE double reference_rounding(const Vec3<T>& r) {
  return 0x1p-23 * (std::fabs(double(r.x)) + std::fabs(double(r.y)) + std::fabs(double(r.z))) +
         0x1p-126;  // subnormal roundings: below the smallest normal fp32
}
GS_HD GS_INLINE double distance_from_reference(const Vec3d& x, const Vec3f& r, const PeriodicBox& box) {
  return norm(box.separation(x, Vec3d(r))) + reference_rounding(r);
}

// What a watched kick-drift tells the host about the list (ListWatch): ints
// set to 1 by any particle, never cleared by a kernel.
struct ListVerdict {
  int stale_next = 0;  // the list may not cover the next step's contacts: rebuild before them
  int fast = 0;        // a list built on these positions would not cover the next step's either
  int stale_now = 0;   // a particle is more than half the skin from where the list saw it...
  ParticleId stale_now_particle = 0;  // ...this one (one of them, where several are)
};

// The margin delta by which a list (with ranks, the halo) is rebuilt ahead of
// half the skin, as a fraction of the skin. The verdict of step n is read only at step
// n + 1, once that step's drift has run (docs/DESIGN.md, "The step's data
// flow"); a particle's move in step n + 1 exceeds its move in step n by at
// most |a| dt^2 (a: its acceleration by the forces of step n), which delta
// must cover. At the stable step |a| dt^2 is about a tenth of a contact's
// overlap (docs/STABILITY.md): a tenth of the skin (at the default 0.1
// diameters) covers overlaps up to about 8 % of a diameter, and makes a slow
// bed's list rebuild a fifth sooner than at half the skin.
constexpr double kListMarginOfSkin = 0.1;

// Sets a verdict's field: many threads may store at once (relaxed atomics on
// the host, where a plain race would be undefined; any one store wins).
template <class T>
GS_HD GS_INLINE void store_flag(T& field, T value) {
#if defined(__CUDA_ARCH__)
  field = value;
#else
  __atomic_store_n(&field, value, __ATOMIC_RELAXED);
#endif
}

// The check of owned particle i (id `id`) after its drift in step n, at x,
// against the list built on `reference` (null where the list no longer
// describes the store: it is rebuilt anyway). With D its distance from where
// the list saw it (to the nearest image: a wrapped particle has moved by that;
// bounded above for the fp32 reference: distance_from_reference), m this
// step's move and delta the margin:
//   stale_next where D + m + delta > skin / 2: where no particle raises it,
//     every particle is still within skin / 2 after step n + 1, unless its
//     move grew by more than delta in one step;
//   fast where m + delta + 2 e > skin / 2, e the rounding bound of x
//     (reference_rounding): a list built after this drift would be stale
//     after the next one, for the same reason, since it would measure from
//     x rounded to fp32 (up to e away) and add e to every distance. Far
//     enough from the origin that 2 e alone passes half the skin, the list
//     is rebuilt every step;
//   stale_now where D > skin / 2. Read at once in the first step of a run
//     (which has no verdict of a step before it); read a step late
//     otherwise, where it tells the host that a list kept on the last step's
//     verdict did not cover this step: the guard of the lag (a fault).
struct ListWatch {
  const Vec3f* reference = nullptr;
  PeriodicBox box;
  double half_skin = 0, margin = 0;
  ListVerdict* verdict = nullptr;  // null: not watched (no skin)

  GS_HD bool active() const { return verdict != nullptr; }
  GS_HD void operator()(Index i, ParticleId id, const Vec3d& x, double move) const {
    const double ahead = move + margin;
    if (ahead + 2 * reference_rounding(x) > half_skin) store_flag(verdict->fast, 1);
    if (!reference) return;
    const double d = distance_from_reference(x, reference[i], box);
    if (d + ahead > half_skin) store_flag(verdict->stale_next, 1);
    if (d > half_skin) {
      store_flag(verdict->stale_now, 1);
      store_flag(verdict->stale_now_particle, id);
    }
  }
};

// What a pass of the GPU's build over the cells does (ListPass).
enum class ListPassKind {
  count,  // the neighbours counted into begin[i + 1] (item 0 also sets begin[0] = 0)
  fill,   // after the scan, written to list[begin[i], begin[i + 1]) and ordered by id
  stage,  // counted, as `count`, and the first `width` written to the particle's
          // row of `width` (list + i * width), ordered by id where they all fit
};

// One pass of the GPU's build over owned particle i (ListPassKind). A small
// scene gives each particle a group of lanes (in_group), as its force kernel
// does: lane r tests candidates r, r + size, ... of each run of cells, and
// the neighbours of a round are written in candidate order, after those of
// the lanes before them; the leader orders them once all are written. The
// order by id makes the list the one a thread alone writes. Elsewhere a
// particle is one lane's.
template <ListPassKind Kind>
struct ListPass {
  // A launch hint: 8 blocks of 128 threads a multiprocessor hold the passes
  // to 64 registers (77 at 4 blocks). They wait on latency, not memory, so
  // the twice as many resident warps pay: a loosening bed of 4e6 ran 2.3 %
  // faster, the same bits (docs/PERFORMANCE.md, "Output without an order").
  static constexpr int kMinBlocksPerSM = 8;
  CellCandidates cells;
  WithinSkin near;
  const ParticleId* id;  // fill and stage
  ListOffset* begin;
  Index* list;    // fill: the list; stage: the rows
  int width = 0;  // stage: the rows' width
  GS_HD void operator()(Index i) const { in_group(i, OneLane{}); }

  template <class Group>
  GS_HD void in_group(Index i, const Group& g) const {
    constexpr bool kFill = Kind == ListPassKind::fill, kStage = Kind == ListPassKind::stage;
    const Vec3d xi = near.position[i];
    Index* out = kStage ? list + std::size_t(i) * std::size_t(width) : list;
    ListOffset k = kFill ? begin[i] : 0;
    auto run = [&](Index first, Index end) {
      for (Index round = first; round < end; round += Index(g.size)) {
        const Index c = round + Index(g.rank);
        const bool hit = c < end && near(i, cells.sorted[c], xi);
        const unsigned votes = g.ballot(hit);
        if constexpr (Kind != ListPassKind::count) {
          const ListOffset at = k + ListOffset(bit_count(votes & ((1u << g.rank) - 1u)));
          if (hit && (!kStage || at < ListOffset(width))) out[at] = cells.sorted[c];
        }
        k += ListOffset(bit_count(votes));
      }
    };
    cells.for_each_run(xi, run);
    if constexpr (kFill) {
      g.sync();
      if (g.leader()) sort_by_id(list + begin[i], Index(k - begin[i]), id);
      return;
    }
    if constexpr (kStage) {
      g.sync();
      if (g.leader() && k <= ListOffset(width)) sort_by_id(out, Index(k), id);
    }
    if (g.leader()) {
      if (i == 0) begin[0] = 0;
      begin[i + 1] = k;
    }
  }
};

// After a staged pass and the scan: owned particle i's row copied to
// list[begin[i], begin[i + 1]), or, where its neighbours outnumbered the
// row, found again by a pass of its own over its cells (`fill`).
struct ListPlace {
  static constexpr int kMinBlocksPerSM = ListPass<ListPassKind::fill>::kMinBlocksPerSM;
  ListPass<ListPassKind::fill> fill;
  const Index* rows;
  int width;
  GS_HD void operator()(Index i) const { in_group(i, OneLane{}); }

  template <class Group>
  GS_HD void in_group(Index i, const Group& g) const {
    const ListOffset first = fill.begin[i], n = fill.begin[i + 1] - first;
    if (n > ListOffset(width)) {
      fill.in_group(i, g);
      return;
    }
    const Index* row = rows + std::size_t(i) * std::size_t(width);
    for (ListOffset r = ListOffset(g.rank); r < n; r += ListOffset(g.size)) fill.list[first + r] = row[r];
  }
};

// The rows' width of a GPU build in one pass (ListPassKind::stage), given
// the bytes the rows may take (`room`: what the build has freed and does
// not hold again until the new list is built) and the old list's entries
// among n particles: 0 (two passes) unless the rows hold twice the old
// mean and more (at most kMaxStagedWidth), so that few particles pass over
// their cells again.
constexpr int kMaxStagedWidth = 32;
inline int staged_list_width(std::size_t room, std::size_t old_entries, std::size_t n) {
  if (n == 0 || old_entries == 0) return 0;
  const std::size_t width = std::min(room / (n * sizeof(Index)), std::size_t(kMaxStagedWidth));
  return width >= 2 * old_entries / n + 1 ? int(width) : 0;
}

// The reverse entries of owned particle i's row (VerletList::reverse). The
// list is symmetric among owned particles (WithinSkin is: the separation
// from either side is the other's exact negation) and each row is in
// ascending id, so i's entry in j's row is found by bisection. A row that
// does not name i (not expected) gets kNoEntry: each side then computes the
// pair alone, as without reverse entries.
struct ReverseEntryKernel {
  const ListOffset* begin;
  const Index* list;
  const ParticleId* id;
  Index n_owned;
  ListOffset* reverse;
  GS_HD void operator()(Index i) const {
    for (ListOffset k = begin[i]; k < begin[i + 1]; ++k) {
      const Index j = list[k];
      reverse[k] = j < n_owned ? entry_naming(j, i) : kNoEntry;
    }
  }
  GS_HD ListOffset entry_naming(Index j, Index i) const {
    const ListOffset end = begin[j + 1];
    const ListOffset at = partition_point(begin[j], end, [&](ListOffset k) { return id[list[k]] < id[i]; });
    return at < end && list[at] == i ? at : kNoEntry;
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
// cell list `cells` (owned and ghosts): Exec::fill_verlet_list finds the
// neighbours, in the backend's memory; then, where each pair is computed once
// (Exec::pairs_once), the reverse entries. The cell list is not read after
// this; the reference positions follow in set_list_references, which a
// build calls last (so they are not held beside the cells or a follower's
// tables at the build's peak: engine/neighbour_finder.hpp).
template <class Exec>
void build_verlet_list(VerletList& v, const CellList& cells, const Vec3d* position, const float* radius,
                       const ParticleId* id, Index n_owned, Index n_total, double skin) {
  Exec::fill_verlet_list(v, CellCandidates{cells.grid, cells.sorted.data(), cells.cell_begin.data()},
                         WithinSkin{position, radius, skin, cells.grid.box}, id, n_owned);
  if constexpr (Exec::pairs_once) {
    v.reverse.resize_discarding(v.list.size());
    Exec::parallel_for(n_owned, ReverseEntryKernel{v.begin.data(), v.list.data(), id, n_owned, v.reverse.data()});
  }
  v.skin = skin;
  v.box = cells.grid.box;
  v.n_owned = n_owned;
  v.n_total = n_total;
  v.valid = true;
}

// The positions the list's staleness is measured from (RoundReference).
template <class Exec>
void set_list_references(VerletList& v, const Vec3d* position) {
  v.reference.resize_discarding(std::size_t(v.n_owned));
  Exec::parallel_for(v.n_owned, RoundReference{position, v.reference.data()});
}

// What a list leaves behind once it no longer describes the store: its
// entries, reverse entries and references, rewritten whole by the next
// build, are freed (its offsets are kept: the next build's count pass
// writes them in place).
inline void discard_spent_list(VerletList& v) {
  v.valid = false;
  v.list.discard();
  v.reverse.discard();
  v.reference.discard();
}

}  // namespace gs
