#include <omp.h>

#include <algorithm>

#include "backend/cpu/cpu_exec.hpp"

namespace gs {

namespace {

// Visitor of the cell candidates: appends the neighbours of particle i.
struct AppendNeighbours {
  const WithinSkin* near;
  Index i;
  Vec3d xi;
  std::vector<Index>* out;
  void operator()(Index j) const {
    if ((*near)(i, j, xi)) out->push_back(j);
  }
};

}  // namespace

// Each thread lists the neighbours of its contiguous share of the particles
// into its own buffer, counting them in begin[i + 1]; after one prefix sum
// over the counts, the buffers are copied into place. One walk of the cells,
// where counting first and filling after would take two.
void CpuExec::fill_verlet_list(VerletList& v, const CellCandidates& cells, const WithinSkin& near,
                               const ParticleId* id, Index n_owned) {
  v.begin.resize(std::size_t(n_owned) + 1);
  Index* begin = v.begin.data();
  begin[0] = 0;
#pragma omp parallel if (n_owned >= kSerialBelow)
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
    v.parts.resize(std::size_t(threads));
    std::vector<Index>& out = v.parts[std::size_t(t)];
    out.clear();
    const Index first = Index(std::int64_t(n_owned) * t / threads);
    const Index last = Index(std::int64_t(n_owned) * (t + 1) / threads);
    for (Index i = first; i < last; ++i) {
      const std::size_t from = out.size();
      const AppendNeighbours append{&near, i, near.position[i], &out};
      cells.for_each(i, append.xi, append);
      sort_by_id(out.data() + from, Index(out.size() - from), id);
      begin[i + 1] = Index(out.size() - from);
    }
#pragma omp barrier
#pragma omp single
    {
      for (Index i = 0; i < n_owned; ++i) begin[i + 1] += begin[i];
      v.list.resize(std::size_t(begin[n_owned]));
    }
    std::copy(out.begin(), out.end(), v.list.data() + begin[first]);
  }
}

}  // namespace gs
