#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "decomposition.hpp"

namespace gs {

// Arbitrary-shaped regions: the coarse cells are partitioned with METIS
// (see metis_partition) and a rank owns the cells of its part. Handles any
// neighbour set (corner/edge contacts included), unlike slabs.
//
// Every rank may compute the partition itself from the same all-reduced
// histogram (the result is deterministic for a given METIS build), or rank 0
// may compute it and broadcast cell_owner() for from_cell_owner().
class MetisDecomposition final : public Decomposition {
 public:
  static constexpr std::int64_t kDefaultMaxCells = 250000;  // graph size: METIS takes well under a second
  static constexpr int kDefaultSeed = 4321;

  // grid: CoarseGrid::make(lo, hi, cell_size, max_cells), so the cell edge is
  // an integer multiple of cell_size and the graph stays small.
  // cell_counts: global particles per coarse cell (cell_histogram, all-reduced).
  // cell_load: empty, or an extra weight per cell (e.g. contacts per cell).
  // n_ranks == 1 never calls METIS.
  MetisDecomposition(const CoarseGrid& grid, int n_ranks, const Histogram& cell_counts,
                     const Histogram& cell_load = {}, int seed = kDefaultSeed);

  // Single-process convenience: builds the grid and the histogram from positions.
  static MetisDecomposition from_positions(const Vec3d& lo, const Vec3d& hi, double cell_size, int n_ranks,
                                           const std::vector<Vec3d>& positions,
                                           std::int64_t max_cells = kDefaultMaxCells, int seed = kDefaultSeed);

  // Adopts a partition computed elsewhere (one part in [0, n_ranks) per cell).
  static MetisDecomposition from_cell_owner(const CoarseGrid& grid, int n_ranks, std::vector<int> cell_owner,
                                            const Histogram& cell_counts);

  // Repartitions from new global per-cell counts (and loads); same grid and seed.
  void rebalance(const Histogram& cell_counts, const Histogram& cell_load = {});
  void rebalance(const std::vector<Vec3d>& positions);  // single-process convenience

  const std::vector<int>& cell_owner() const { return cell_owner_; }  // part per CoarseGrid::index
  const std::vector<std::int64_t>& loads() const { return loads_; }   // particles per rank

  int n_ranks() const override { return n_ranks_; }
  int owner(const Vec3d& x) const override { return cell_owner_[std::size_t(grid_.cell_of(x))]; }
  void ranks_near(const Vec3d& x, double halo_width, int self, std::vector<int>& out) const override;
  std::vector<int> neighbours(int rank) const override;
  double imbalance() const override { return imbalance_; }
  std::string describe() const override;
  OwnerMapHost owner_map() const override;
  const CoarseGrid& grid() const override { return grid_; }

 private:
  MetisDecomposition(const CoarseGrid& grid, int n_ranks, int seed);
  void adopt(std::vector<int> cell_owner, const Histogram& cell_counts);

  CoarseGrid grid_;
  int n_ranks_ = 1;
  int seed_ = kDefaultSeed;
  std::vector<int> cell_owner_;
  std::vector<std::vector<int>> neighbours_;  // sorted, per rank
  std::vector<std::int64_t> loads_;
  double imbalance_ = 1.0;
};

}  // namespace gs
