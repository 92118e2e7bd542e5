#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

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
  ListOffset* begin = v.begin.data();
  begin[0] = 0;
  bool too_long = false;  // set by one thread, read after the barrier of `single`
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
      begin[i + 1] = ListOffset(out.size() - from);
    }
#pragma omp barrier
#pragma omp single
    {
      std::uint64_t total = 0;
      for (Index i = 0; i < n_owned; ++i) begin[i + 1] = ListOffset(total += begin[i + 1]);
      if (total > std::numeric_limits<ListOffset>::max()) too_long = true;
      else v.list.resize_discarding(std::size_t(total));  // rewritten whole: no copy of the old
    }
    if (!too_long) std::copy(out.begin(), out.end(), v.list.data() + begin[first]);
  }
  if (too_long) throw std::runtime_error("the Verlet list would hold 2^32 entries or more (32-bit offsets)");
}

}  // namespace gs
