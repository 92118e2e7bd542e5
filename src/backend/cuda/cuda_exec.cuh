#pragma once
// CUDA execution policy: one thread per particle, CUB radix sort for keys.
#include <stdexcept>
#include <string>
#include <type_traits>

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>
#include <thrust/iterator/counting_iterator.h>

#include "backend/backend.hpp"
#include "backend/check.hpp"
#include "backend/cuda/lane_group.cuh"
#include "backend/device_array.hpp"
#include "backend/launch_hints.hpp"
#include "core/history_layout.hpp"
#include "core/id_range.hpp"
#include "neighbor/cell_list.hpp"
#include "neighbor/verlet_list.hpp"

namespace gs {

constexpr int kCudaBlock = 128;

template <class F>
__global__ void for_each_kernel(Index n, F f) {
  const Index i = Index(blockIdx.x) * Index(blockDim.x) + Index(threadIdx.x);
  if (i < n) f(i);
}

// The same, for a functor that asks for at least MinBlocks resident blocks
// per multiprocessor (backend/launch_hints.hpp): ptxas then caps its registers.
template <class F, int MinBlocks>
__global__ void __launch_bounds__(kCudaBlock, MinBlocks) for_each_kernel_bounded(Index n, F f) {
  const Index i = Index(blockIdx.x) * Index(blockDim.x) + Index(threadIdx.x);
  if (i < n) f(i);
}

// The same with a group of `lanes` threads per i (backend/cuda/lane_group.cuh),
// which call f.in_group(i, group).
template <class F, int MinBlocks>
__global__ void __launch_bounds__(kCudaBlock, MinBlocks) for_each_group_kernel(Index n, int lanes, F f) {
  const long long thread = (long long)blockIdx.x * blockDim.x + threadIdx.x;
  const Index i = Index(thread / lanes);
  if (i < n) f.in_group(i, LaneGroup(lanes));
}

// What a scan of counts into offsets begin[0, n] came to, for one read-back:
// out[0] = 1 where it wrapped past 2^32 (OffsetsWrapped: any thread's store
// wins; out[0] is zeroed before), out[1] the total.
template <class Wrapped>
__global__ void scan_outcome_kernel(Index n, Wrapped wrapped, ListOffset* out) {
  const Index i = Index(blockIdx.x) * Index(blockDim.x) + Index(threadIdx.x);
  if (i < n && wrapped(i)) out[0] = 1;
  if (i == n - 1) out[1] = wrapped.begin[n];
}

struct CudaExec {
  static constexpr Backend backend = Backend::cuda;
  static constexpr int kBlock = kCudaBlock;
  // Neighbouring threads read the same slot of neighbouring particles: coalesced.
  static constexpr HistoryOrder history_order = HistoryOrder::slot_major;
  // Cell offsets one thread per cell, so no thread walks a long empty stretch.
  static constexpr bool cell_begins_by_particle = false;
  // The cell sort's keys are the cells alone: CUB passes over every key bit
  // up to the highest (8 a pass), and ids would add 32 bits, four of mixer
  // case a's six passes. Each row of the Verlet list is sorted by id anyway
  // (ListPass), so no result depends on a cell's order.
  static constexpr bool cell_keys_hold_ids = false;
  // Contacts from a Verlet list (neighbor/verlet_list.hpp says why).
  static constexpr bool verlet_list = true;
  // Each thread computes its particle's side of every pair (CpuExec::pairs_once):
  // a second pass and the loads per entry would add memory traffic that has
  // not been measured against the laws saved.
  static constexpr bool pairs_once = false;

  template <class F>
  static void parallel_for(Index n, const F& f) {
    if (n <= 0) return;
    const unsigned blocks = unsigned((n + kBlock - 1) / kBlock);
    if constexpr (MinBlocksPerSM<F>::value > 0)
      for_each_kernel_bounded<F, MinBlocksPerSM<F>::value><<<blocks, kBlock>>>(n, f);
    else
      for_each_kernel<<<blocks, kBlock>>>(n, f);
    GS_CUDA_CHECK(cudaGetLastError());
  }

  // f over [0, n) with force_lanes(n, setting) lanes per i (F::in_group), or
  // one thread each (parallel_for) where that is one lane: a scene too small
  // to fill the GPU lasts as long as its longest particle, whose work its lanes share.
  // A setting of 1-32 fixes the lanes (engine/pair_history.hpp, kRowLanes:
  // the rows of the pair tables, for coalesced reads and writes).
  template <class F>
  static void parallel_for_lanes(Index n, int setting, const F& f) {
    const int lanes = force_lanes(n, setting);
    if (lanes == 1) return parallel_for(n, f);
    if (n <= 0) return;
    static_assert(GroupBlocksPerSM<F>::value > 0, "a functor run in lane groups names its resident blocks");
    const long long threads = (long long)n * lanes;
    const unsigned blocks = unsigned((threads + kBlock - 1) / kBlock);
    for_each_group_kernel<F, GroupBlocksPerSM<F>::value><<<blocks, kBlock>>>(n, lanes, f);
    GS_CUDA_CHECK(cudaGetLastError());
  }

  // Bytes of CUB's own storage for sort_pairs of n keys.
  template <class Key>
  static std::size_t sort_storage_bytes(Index n, int key_bits) {
    cub::DoubleBuffer<Key> keys(nullptr, nullptr);
    cub::DoubleBuffer<Index> values(nullptr, nullptr);
    std::size_t bytes = 0;
    GS_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keys, values, n, 0, key_bits));
    return bytes;
  }
  // Sorts p's keys ascending, carrying the values along, with `bytes` of
  // storage (sort_storage_bytes) at `storage`.
  template <class Key>
  static void sort_pairs(SortPairs<Key>& p, void* storage, std::size_t bytes) {
    cub::DoubleBuffer<Key> keys(p.keys, p.keys_alt);
    cub::DoubleBuffer<Index> values(p.values, p.values_alt);
    GS_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(storage, bytes, keys, values, p.n, 0, p.key_bits));
    p.keys = keys.Current();
    p.values = values.Current();
  }

  // The smallest and the largest of id[0, n), n > 0: CUB's reductions, their
  // storage in `scratch`, the two read back.
  static IdRange id_range(const ParticleId* id, Index n, DeviceArray<unsigned char>& scratch) {
    std::size_t min_bytes = 0, max_bytes = 0;
    GS_CUDA_CHECK(cub::DeviceReduce::Min(nullptr, min_bytes, id, static_cast<ParticleId*>(nullptr), n));
    GS_CUDA_CHECK(cub::DeviceReduce::Max(nullptr, max_bytes, id, static_cast<ParticleId*>(nullptr), n));
    constexpr std::size_t kResultBytes = 256;  // the two results first, CUB's storage aligned after them
    scratch.resize_discarding(kResultBytes + std::max(min_bytes, max_bytes));
    ParticleId* result = reinterpret_cast<ParticleId*>(scratch.data());
    GS_CUDA_CHECK(cub::DeviceReduce::Min(scratch.data() + kResultBytes, min_bytes, id, result, n));
    GS_CUDA_CHECK(cub::DeviceReduce::Max(scratch.data() + kResultBytes, max_bytes, id, result + 1, n));
    ParticleId read[2] = {0, 0};
    GS_CUDA_CHECK(cudaMemcpy(read, result, sizeof read, cudaMemcpyDeviceToHost));
    return {read[0], read[1]};
  }

  // Writes the indices i in [0, n) with pred(i), ascending, to out; returns
  // how many (CUB's stable selection; the count comes back to the host).
  template <class P>
  static Index select(Index n, const P& pred, Index* out, DeviceArray<unsigned char>& scratch) {
    if (n <= 0) return 0;
    const thrust::counting_iterator<Index> first(0);
    std::size_t bytes = 0;
    GS_CUDA_CHECK(cub::DeviceSelect::If(nullptr, bytes, first, out, static_cast<Index*>(nullptr), n, pred));
    constexpr std::size_t kCountBytes = 256;  // the count first, CUB's storage aligned after it
    scratch.resize_discarding(kCountBytes + bytes);
    Index* count = reinterpret_cast<Index*>(scratch.data());
    GS_CUDA_CHECK(cub::DeviceSelect::If(scratch.data() + kCountBytes, bytes, first, out, count, n, pred));
    Index m = 0;
    GS_CUDA_CHECK(cudaMemcpy(&m, count, sizeof(Index), cudaMemcpyDeviceToHost));
    return m;
  }

  // Turns counts begin[1, n] into offsets (an in-place inclusive sum; begin[0]
  // = 0 is the caller's) with CUB's storage in `scratch`, and returns the
  // total (read back: a build waits for the device anyway). A total of 2^32
  // or more wraps past 32-bit offsets: refused, naming `what` (the check's
  // flag comes back with the total, in one read); a null `what` skips the
  // check's kernel, for a caller that bounded the total.
  static ListOffset scan_counts(ListOffset* begin, Index n, DeviceArray<unsigned char>& scratch, const char* what) {
    if (n <= 0) return 0;
    std::size_t bytes = 0;
    GS_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, bytes, begin + 1, begin + 1, n));
    constexpr std::size_t kOutcomeBytes = 256;  // the outcome first, CUB's storage aligned after it
    scratch.resize_discarding(kOutcomeBytes + bytes);
    ListOffset* outcome = reinterpret_cast<ListOffset*>(scratch.data());
    GS_CUDA_CHECK(cub::DeviceScan::InclusiveSum(scratch.data() + kOutcomeBytes, bytes, begin + 1, begin + 1, n));
    ListOffset read[2] = {0, 0};  // wrapped, total
    if (what != nullptr) {
      GS_CUDA_CHECK(cudaMemsetAsync(outcome, 0, sizeof(ListOffset), 0));
      scan_outcome_kernel<<<unsigned((n + kBlock - 1) / kBlock), kBlock>>>(n, OffsetsWrapped{begin}, outcome);
      GS_CUDA_CHECK(cudaGetLastError());
      GS_CUDA_CHECK(cudaMemcpy(read, outcome, sizeof read, cudaMemcpyDeviceToHost));
      if (read[0] != 0) throw std::runtime_error(std::string(what) + " would hold 2^32 entries or more (32-bit offsets)");
    } else {
      GS_CUDA_CHECK(cudaMemcpy(&read[1], begin + n, sizeof(ListOffset), cudaMemcpyDeviceToHost));
    }
    return read[1];
  }

  // Fills v.begin and v.list: the neighbours of particles [0, n_owned) among
  // `cells`, each particle's in ascending id (ListPass, with as many lanes
  // per particle as the forces take). Where v.staged_width allows, one pass
  // over the cells into rows of that width, an in-place inclusive scan of
  // the counts, and the rows copied into place (ListPlace); else two passes
  // (count, fill) around the scan. The total comes back to the host to size
  // the list.
  static void fill_verlet_list(VerletList& v, const CellCandidates& cells, const WithinSkin& near,
                               const ParticleId* id, Index n_owned) {
    v.begin.resize(std::size_t(n_owned) + 1);
    ListOffset* begin = v.begin.data();
    if (n_owned == 0) {
      GS_CUDA_CHECK(cudaMemset(begin, 0, sizeof(ListOffset)));
      v.list.resize(0);
      return;
    }
    const int width = v.staged_width;
    DeviceArray<Index> rows(backend);
    if (width > 0) {
      rows.resize_discarding(std::size_t(n_owned) * std::size_t(width));
      parallel_for_lanes(n_owned, v.lanes_setting,
                         ListPass<ListPassKind::stage>{cells, near, id, begin, rows.data(), width});
    } else {
      parallel_for_lanes(n_owned, v.lanes_setting, ListPass<ListPassKind::count>{cells, near, id, begin, nullptr});
    }
    const ListOffset total = scan_counts(begin, n_owned, v.scan_scratch, "the Verlet list");
    v.list.resize_discarding(std::size_t(total));  // rewritten whole: no copy of the old
    const ListPass<ListPassKind::fill> fill{cells, near, id, begin, v.list.data()};
    if (width > 0) parallel_for_lanes(n_owned, v.lanes_setting, ListPlace{fill, rows.data(), width});
    else parallel_for_lanes(n_owned, v.lanes_setting, fill);
  }

  static void synchronize() { GS_CUDA_CHECK(cudaDeviceSynchronize()); }
};

}  // namespace gs
