#pragma once
// CPU execution policy: OpenMP over particles, an O(N) radix sort for keys.
#include "backend/backend.hpp"
#include "neighbor/cell_list.hpp"

namespace gs {

struct CpuExec {
  static constexpr Backend backend = Backend::cpu;

  template <class F>
  static void parallel_for(Index n, const F& f) {
#pragma omp parallel for schedule(static)
    for (Index i = 0; i < n; ++i) f(i);
  }

  // Sorts c.keys[0,n) ascending, carrying c.sorted along.
  static void sort_pairs(CellList& c, Index n);
  static void synchronize() {}
};

}  // namespace gs
