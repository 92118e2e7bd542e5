#pragma once
// A per-particle functor run over a list of store indices instead of a
// range: item k of the launch is particle index[k]. It keeps what the
// execution policies ask of the functor it wraps (resident blocks, lane
// groups: backend/cuda/cuda_exec.cuh), so a subset of the particles runs as
// the whole store would, each particle's work unchanged.
#include "backend/launch_hints.hpp"
#include "core/hd.hpp"
#include "core/types.hpp"

namespace gs {

template <class F>
struct AtIndices {
  static constexpr int kMinBlocksPerSM = F::kMinBlocksPerSM;
  static constexpr int kGroupBlocksPerSM = GroupBlocksPerSM<F>::value;
  F f;
  const Index* index;  // backend memory

  GS_HD GS_INLINE void operator()(Index k) const { f(index[k]); }
#if defined(__CUDACC__)
  template <class Group>
  __device__ void in_group(Index k, const Group& g) const {
    f.in_group(index[k], g);
  }
#endif
};

}  // namespace gs
