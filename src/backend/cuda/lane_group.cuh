#pragma once
// A group of `size` consecutive lanes of a warp (size a power of two up to
// 32) that work on one particle: its rank, its vote, and a value shuffled from
// one of its lanes. engine/force_kernel.hpp (in_group) says what for.
#include "core/vec3.hpp"

namespace gs {

struct LaneGroup {
  int size;       // lanes in the group
  int rank;       // this lane's place in it: 0 leads
  int first;      // the warp lane of rank 0
  unsigned mask;  // the group's lanes in the warp

  __device__ explicit LaneGroup(int lanes) : size(lanes) {
    const int lane = int(threadIdx.x % 32u);
    rank = lane % lanes;
    first = lane - rank;
    mask = (lanes == 32 ? 0xffffffffu : (1u << lanes) - 1u) << first;
  }
  __device__ bool leader() const { return rank == 0; }
  // Waits for the group's lanes; what each wrote before is then seen by all.
  __device__ void sync() const { __syncwarp(mask); }
  // Bit r set where lane r of the group votes true; the same on every lane.
  __device__ unsigned ballot(bool vote) const { return (__ballot_sync(mask, vote) & mask) >> first; }
  template <class T>
  __device__ T shuffle(T v, int from) const {
    return __shfl_sync(mask, v, from, size);
  }
  template <class T>
  __device__ Vec3<T> shuffle(const Vec3<T>& v, int from) const {
    return Vec3<T>(shuffle(v.x, from), shuffle(v.y, from), shuffle(v.z, from));
  }
};

}  // namespace gs
