#pragma once
// What a per-particle functor asks of a GPU launch (backend/cuda/cuda_exec.cuh):
// resident blocks per multiprocessor, by which ptxas caps its registers; 0
// where it names none. kMinBlocksPerSM is for one thread per particle;
// kGroupBlocksPerSM, where named, for a group of lanes per particle, else
// the same. A kernel's best hint may differ between the two: a group's
// lanes hold more live state (the shuffles, the mesh's shared scan).
#include <type_traits>

namespace gs {

template <class F, class = void>
struct MinBlocksPerSM {
  static constexpr int value = 0;
};
template <class F>
struct MinBlocksPerSM<F, std::void_t<decltype(F::kMinBlocksPerSM)>> {
  static constexpr int value = F::kMinBlocksPerSM;
};

template <class F, class = void>
struct GroupBlocksPerSM {
  static constexpr int value = MinBlocksPerSM<F>::value;
};
template <class F>
struct GroupBlocksPerSM<F, std::void_t<decltype(F::kGroupBlocksPerSM)>> {
  static constexpr int value = F::kGroupBlocksPerSM;
};

}  // namespace gs
