#include "metis_decomposition.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "metis_partition.hpp"

namespace gs {
namespace {

void add_link(std::vector<int>& list, int rank) {
  // Neighbouring cells mostly repeat the last pair seen; skipping that keeps
  // the lists short before the final sort.
  if (list.empty() || list.back() != rank) list.push_back(rank);
}

// The 13 offsets of the 26-neighbourhood that point "forwards"; visiting them
// from every cell visits every adjacent pair of cells exactly once.
bool is_forward(int dx, int dy, int dz) { return dz > 0 || (dz == 0 && (dy > 0 || (dy == 0 && dx > 0))); }

// Ranks owning cells that share a face, edge or corner: these are the ranks a
// point can be within one cell edge (>= cell_size) of.
std::vector<std::vector<int>> part_adjacency(const CoarseGrid& g, const std::vector<int>& owner, int n_ranks) {
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(n_ranks));
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const int p = owner[std::size_t(g.index(i, j, k))];
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int a = i + dx, b = j + dy, c = k + dz;
              if (!is_forward(dx, dy, dz) || a < 0 || b < 0 || c < 0 || a >= g.dims[0] || b >= g.dims[1] ||
                  c >= g.dims[2])
                continue;
              const int q = owner[std::size_t(g.index(a, b, c))];
              if (p == q) continue;
              add_link(adj[std::size_t(p)], q);
              add_link(adj[std::size_t(q)], p);
            }
      }
  for (auto& list : adj) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return adj;
}

}  // namespace

MetisDecomposition::MetisDecomposition(const CoarseGrid& grid, int n_ranks, int seed)
    : grid_(grid), n_ranks_(n_ranks), seed_(seed) {
  if (n_ranks < 1) throw std::invalid_argument("MetisDecomposition: n_ranks must be >= 1");
}

MetisDecomposition::MetisDecomposition(const CoarseGrid& grid, int n_ranks, const Histogram& cell_counts,
                                       const Histogram& cell_load, int seed)
    : MetisDecomposition(grid, n_ranks, seed) {
  rebalance(cell_counts, cell_load);
}

MetisDecomposition MetisDecomposition::from_positions(const Vec3d& lo, const Vec3d& hi, double cell_size,
                                                      int n_ranks, const std::vector<Vec3d>& positions,
                                                      std::int64_t max_cells, int seed) {
  const CoarseGrid grid = CoarseGrid::make(lo, hi, cell_size, max_cells);
  return MetisDecomposition(grid, n_ranks, cell_histogram(grid, positions), {}, seed);
}

MetisDecomposition MetisDecomposition::from_cell_owner(const CoarseGrid& grid, int n_ranks,
                                                       std::vector<int> cell_owner, const Histogram& cell_counts) {
  MetisDecomposition d(grid, n_ranks, kDefaultSeed);
  d.adopt(std::move(cell_owner), cell_counts);
  return d;
}

void MetisDecomposition::rebalance(const Histogram& cell_counts, const Histogram& cell_load) {
  adopt(metis_partition(grid_, n_ranks_, cell_counts, cell_load, seed_), cell_counts);
}

void MetisDecomposition::rebalance(const std::vector<Vec3d>& positions) {
  rebalance(cell_histogram(grid_, positions));
}

void MetisDecomposition::adopt(std::vector<int> cell_owner, const Histogram& cell_counts) {
  const std::size_t n = std::size_t(grid_.n_cells());
  if (cell_owner.size() != n || cell_counts.size() != n)
    throw std::invalid_argument("MetisDecomposition: need one owner and one count per coarse cell (" +
                                std::to_string(n) + ")");
  std::vector<std::int64_t> loads(std::size_t(n_ranks_), 0);
  for (std::size_t c = 0; c < n; ++c) {
    if (cell_owner[c] < 0 || cell_owner[c] >= n_ranks_)
      throw std::invalid_argument("MetisDecomposition: cell owner " + std::to_string(cell_owner[c]) + " out of range");
    loads[std::size_t(cell_owner[c])] += cell_counts[c];
  }
  neighbours_ = part_adjacency(grid_, cell_owner, n_ranks_);
  cell_owner_ = std::move(cell_owner);
  loads_ = std::move(loads);
  imbalance_ = load_imbalance(loads_);
}

void MetisDecomposition::ranks_near(const Vec3d& x, double halo_width, int self, std::vector<int>& out) const {
  std::array<int, 3> first{}, last{};
  grid_.cells_near(x, halo_width, first, last);
  const std::size_t start = out.size();  // dedupe only what this call appends
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i) {
        const int r = cell_owner_[std::size_t(grid_.index(i, j, k))];
        if (r != self && std::find(out.begin() + std::ptrdiff_t(start), out.end(), r) == out.end()) out.push_back(r);
      }
}

OwnerMapHost MetisDecomposition::owner_map() const {
  const std::int64_t nx = grid_.dims[0], ny = grid_.dims[1];
  return {grid_.owner_map_shape({1, nx, nx * ny}), cell_owner_};
}

std::vector<int> MetisDecomposition::neighbours(int rank) const {
  if (rank < 0 || rank >= n_ranks_) throw std::out_of_range("MetisDecomposition::neighbours: rank out of range");
  return neighbours_[std::size_t(rank)];
}

std::string MetisDecomposition::describe() const {
  std::size_t most = 0;
  for (const auto& list : neighbours_) most = std::max(most, list.size());
  std::ostringstream s;
  s << "METIS over " << grid_.dims[0] << "x" << grid_.dims[1] << "x" << grid_.dims[2] << " coarse cells: " << n_ranks_
    << " ranks, imbalance " << std::fixed << std::setprecision(2) << imbalance_ << ", at most " << most
    << " neighbours per rank";
  return s.str();
}

}  // namespace gs
