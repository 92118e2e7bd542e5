#pragma once
// CPU execution policy: OpenMP over particles, an O(N) radix sort for keys.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "backend/backend.hpp"
#include "backend/device_array.hpp"
#include "core/history_layout.hpp"
#include "core/id_range.hpp"
#include "neighbor/cell_list.hpp"
#include "neighbor/verlet_list.hpp"

namespace gs {

struct CpuExec {
  static constexpr Backend backend = Backend::cpu;
  // One thread walks all slots of its particle: keep them in one cache line.
  static constexpr HistoryOrder history_order = HistoryOrder::particle_major;
  // Cell offsets in one O(n + cells) walk over the sorted particles.
  static constexpr bool cell_begins_by_particle = true;
  // The cell sort's keys hold the ids too: a cell's particles come in id
  // order, which the list's per-row sort by id then finds done (the sort
  // itself passes only over the bits in which keys differ).
  static constexpr bool cell_keys_hold_ids = true;
  // Contacts from a Verlet list (neighbor/verlet_list.hpp says why).
  static constexpr bool verlet_list = true;
  // Each touching pair's law once for both spheres, in a first pass over the
  // list, then each particle's sums in a second (engine/force_kernel.hpp,
  // pairs_of): a core evaluates half the laws, for a second pass and 29
  // bytes per list entry (docs/PERFORMANCE.md, "Each pair once").
  static constexpr bool pairs_once = true;

  // Each thread calls its own copy of the functor: the compiler then knows
  // that no store through the functor's output pointers changes its fields,
  // so they stay in registers instead of being reloaded around every store.
  // Small loops run on the calling thread: waking a team costs more than
  // they do, and far more when the cores are shared.
  static constexpr Index kSerialBelow = 4096;
  template <class F>
  static void parallel_for(Index n, const F& f) {
#pragma omp parallel if (n >= kSerialBelow)
    {
      const F local = f;
#pragma omp for schedule(static)
      for (Index i = 0; i < n; ++i) local(i);
    }
  }

  // One thread per i: the GPU's lane groups (backend/cuda/cuda_exec.cuh) serve
  // scenes too small to fill it, and coalesce the reads of table rows; a CPU
  // core runs a particle's contacts, or its row, in turn.
  template <class F>
  static void parallel_for_lanes(Index n, int /*setting*/, const F& f) {
    parallel_for(n, f);
  }

  // The smallest and the largest of id[0, n), n > 0 (every host thread).
  static IdRange id_range(const ParticleId* id, Index n, DeviceArray<unsigned char>& /*scratch*/) {
    ParticleId lowest = id[0], highest = id[0];
#pragma omp parallel for reduction(min : lowest) reduction(max : highest) if (n >= kSerialBelow)
    for (Index k = 0; k < n; ++k) {
      lowest = std::min(lowest, id[k]);
      highest = std::max(highest, id[k]);
    }
    return {lowest, highest};
  }

  // How many of flags[0, n) are not zero (every host thread).
  static std::size_t count_set(const std::uint8_t* flags, std::size_t n) {
    std::size_t count = 0;
#pragma omp parallel for reduction(+ : count) schedule(static) if (n >= std::size_t(kSerialBelow))
    for (std::size_t k = 0; k < n; ++k) count += flags[k] != 0;
    return count;
  }

  // Writes the indices i in [0, n) with pred(i), ascending, to out; returns
  // how many. One pass on the calling thread: it runs on a rank's owned
  // particles once or twice a step, next to a force loop that costs far more.
  template <class P>
  static Index select(Index n, const P& pred, Index* out, DeviceArray<unsigned char>& /*scratch*/) {
    Index m = 0;
    for (Index i = 0; i < n; ++i)
      if (pred(i)) out[m++] = i;
    return m;
  }

  // Turns counts begin[1, n] into offsets (an in-place inclusive sum on the
  // calling thread; begin[0] = 0 is the caller's) and returns the total. A
  // total of 2^32 or more would wrap past 32-bit offsets: refused, naming
  // `what` (or a logic error where `what` is null: the caller bounded it).
  static ListOffset scan_counts(ListOffset* begin, Index n, DeviceArray<unsigned char>& /*scratch*/,
                                const char* what) {
    std::uint64_t total = 0;
    for (Index i = 0; i < n; ++i) begin[i + 1] = ListOffset(total += begin[i + 1]);
    if (total > std::numeric_limits<ListOffset>::max()) {
      if (what == nullptr) throw std::logic_error("a scan bounded below 2^32 passed it");
      throw std::runtime_error(std::string(what) + " would hold 2^32 entries or more (32-bit offsets)");
    }
    return ListOffset(total);
  }

  // Fills v.begin and v.list: the neighbours of particles [0, n_owned) among
  // `cells`, each particle's in ascending id. One pass over the cells.
  static void fill_verlet_list(VerletList& v, const CellCandidates& cells, const WithinSkin& near,
                               const ParticleId* id, Index n_owned);

  // Sorts p's keys ascending, carrying the values along (no storage of its own).
  template <class Key>
  static std::size_t sort_storage_bytes(Index /*n*/, int /*key_bits*/) {
    return 0;
  }
  template <class Key>
  static void sort_pairs(SortPairs<Key>& p, void* /*storage*/, std::size_t /*bytes*/);
  static void synchronize() {}
};

}  // namespace gs
