#include "metis_partition.hpp"

#include <metis.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace gs {
namespace {

// Total vertex weight kept below this so that METIS's idx_t sums of vertex
// weights and of edge weights (each vertex has <= 6 edges, each weighing at
// most about its heavier cell) stay far from 2^31.
constexpr std::int64_t kMaxTotalWeight = std::int64_t(1) << 26;
// With this many cells the edge-weight sum is at most 6 (2 * 2^24 + 2^26) < 2^30.
constexpr std::int64_t kMaxCells = std::int64_t(1) << 24;

struct CsrGraph {
  std::vector<idx_t> xadj, adjncy, vwgt, adjwgt;
};

const char* metis_code_name(int code) {
  switch (code) {
    case METIS_ERROR_INPUT: return "METIS_ERROR_INPUT";
    case METIS_ERROR_MEMORY: return "METIS_ERROR_MEMORY";
    case METIS_ERROR: return "METIS_ERROR";
    default: return "unknown code";
  }
}

void check_metis(int code, const char* call) {
  if (code == METIS_OK) return;
  throw std::runtime_error(std::string(call) + " failed with code " + std::to_string(code) + " (" +
                           metis_code_name(code) + ")");
}

void check_inputs(const CoarseGrid& grid, int n_parts, const Histogram& counts, const Histogram& load) {
  const std::int64_t n = grid.n_cells();
  if (n > kMaxCells)
    throw std::invalid_argument("metis_partition: " + std::to_string(n) + " coarse cells exceed the limit of " +
                                std::to_string(kMaxCells) + " for 32-bit METIS weights; lower max_cells");
  if (n_parts < 1 || n_parts > n)
    throw std::invalid_argument("metis_partition: need 1 <= parts <= coarse cells, got " + std::to_string(n_parts) +
                                " parts for " + std::to_string(n) + " cells");
  if (counts.size() != std::size_t(n) || (!load.empty() && load.size() != std::size_t(n)))
    throw std::invalid_argument("metis_partition: per-cell vectors must have one entry per coarse cell (" +
                                std::to_string(n) + ")");
  for (std::size_t c = 0; c < counts.size(); ++c)
    if (counts[c] < 0 || (!load.empty() && load[c] < 0))
      throw std::invalid_argument("metis_partition: negative particle count or load");
}

// 1 + (particles + load) / f with the smallest integer f that keeps the total in range.
std::vector<idx_t> vertex_weights(const Histogram& counts, const Histogram& load) {
  std::int64_t total = 0;
  for (std::size_t c = 0; c < counts.size(); ++c) total += counts[c] + (load.empty() ? 0 : load[c]);
  const std::int64_t f = std::max<std::int64_t>(1, (total + kMaxTotalWeight - 1) / kMaxTotalWeight);
  std::vector<idx_t> w(counts.size());
  for (std::size_t c = 0; c < counts.size(); ++c) w[c] = idx_t(1 + (counts[c] + (load.empty() ? 0 : load[c])) / f);
  return w;
}

// Face neighbours in a fixed order (-x, +x, -y, +y, -z, +z) so the graph, and
// hence METIS's answer, is the same on every rank.
CsrGraph build_graph(const CoarseGrid& grid, std::vector<idx_t> vwgt) {
  static const int kOffsets[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  CsrGraph g;
  g.vwgt = std::move(vwgt);
  g.xadj.reserve(g.vwgt.size() + 1);
  g.xadj.push_back(0);
  for (int k = 0; k < grid.dims[2]; ++k)
    for (int j = 0; j < grid.dims[1]; ++j)
      for (int i = 0; i < grid.dims[0]; ++i) {
        const idx_t self = idx_t(grid.index(i, j, k));
        for (const auto& o : kOffsets) {
          const int a = i + o[0], b = j + o[1], c = k + o[2];
          if (a < 0 || b < 0 || c < 0 || a >= grid.dims[0] || b >= grid.dims[1] || c >= grid.dims[2]) continue;
          const idx_t other = idx_t(grid.index(a, b, c));
          g.adjncy.push_back(other);
          g.adjwgt.push_back(1 + (g.vwgt[std::size_t(self)] + g.vwgt[std::size_t(other)]) / 2);
        }
        g.xadj.push_back(idx_t(g.adjncy.size()));
      }
  return g;
}

std::vector<int> call_metis(CsrGraph& g, int n_parts, int seed) {
  idx_t options[METIS_NOPTIONS];
  check_metis(METIS_SetDefaultOptions(options), "METIS_SetDefaultOptions");
  options[METIS_OPTION_SEED] = idx_t(seed);
  options[METIS_OPTION_NUMBERING] = 0;
  idx_t nvtxs = idx_t(g.vwgt.size()), ncon = 1, nparts = idx_t(n_parts), edgecut = 0;
  std::vector<idx_t> part(g.vwgt.size(), 0);
  // Recursive bisection is METIS's recommended method for 2 parts; k-way for
  // more, asked for contiguous parts (the cell graph is connected) so each
  // rank's region is one piece with fewer neighbours.
  if (n_parts == 2) {
    check_metis(METIS_PartGraphRecursive(&nvtxs, &ncon, g.xadj.data(), g.adjncy.data(), g.vwgt.data(), nullptr,
                                         g.adjwgt.data(), &nparts, nullptr, nullptr, options, &edgecut, part.data()),
                "METIS_PartGraphRecursive");
  } else {
    options[METIS_OPTION_CONTIG] = 1;
    check_metis(METIS_PartGraphKway(&nvtxs, &ncon, g.xadj.data(), g.adjncy.data(), g.vwgt.data(), nullptr,
                                    g.adjwgt.data(), &nparts, nullptr, nullptr, options, &edgecut, part.data()),
                "METIS_PartGraphKway");
  }
  std::vector<int> out(part.begin(), part.end());
  for (int p : out)
    if (p < 0 || p >= n_parts) throw std::runtime_error("METIS returned part " + std::to_string(p) + " out of range");
  return out;
}

}  // namespace

std::vector<int> metis_partition(const CoarseGrid& grid, int n_parts, const Histogram& cell_counts,
                                 const Histogram& cell_load, int seed) {
  check_inputs(grid, n_parts, cell_counts, cell_load);
  if (n_parts == 1) return std::vector<int>(cell_counts.size(), 0);  // METIS is neither needed nor asked
  CsrGraph g = build_graph(grid, vertex_weights(cell_counts, cell_load));
  return call_metis(g, n_parts, seed);
}

}  // namespace gs
