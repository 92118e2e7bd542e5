#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "decomposition.hpp"

namespace gs {

// Slabs along one axis: rank r owns the coarse-cell layers
// [layer_bounds()[r], layer_bounds()[r+1]) along axis() (and everything
// beyond the domain in the other axes, and below / above the domain for the
// first / last rank). Bounds are integer layer indices, so they are exact and
// identical on every rank; they are a pure function of the global histogram
// of particles per layer (see balanced_cuts), hence independent of particle
// order and of how particles are spread over ranks.
class SlabDecomposition final : public Decomposition {
 public:
  // Core constructor. grid: CoarseGrid::make(lo, hi, cell_size) (no cell
  // cap: only the layers along one axis matter). layer_counts: global
  // particles per layer along axis (size grid.dims[axis]; the caller
  // all-reduces the per-rank layer_histogram). axis: 0, 1 or 2.
  // Throws std::runtime_error if the domain has fewer than n_ranks layers
  // along axis (each slab must be at least one coarse cell thick).
  SlabDecomposition(const CoarseGrid& grid, int n_ranks, int axis, const Histogram& layer_counts);

  // axis -1 picks the axis automatically (see pick_axis); otherwise as above.
  static SlabDecomposition from_histograms(const CoarseGrid& grid, int n_ranks, int axis,
                                           const LayerHistograms& histograms);
  // Single-process convenience: builds the grid and histograms from positions.
  static SlabDecomposition from_positions(const Vec3d& lo, const Vec3d& hi, double cell_size, int n_ranks,
                                          int axis, const std::vector<Vec3d>& positions);

  // Among the axes with at least n_ranks layers, the one along which the
  // particles' bounding box (in whole layers, from the histograms) is
  // longest; no particles: the longest domain axis. Ties: lowest axis.
  // Throws std::runtime_error when no axis has n_ranks layers.
  static int pick_axis(const CoarseGrid& grid, int n_ranks, const LayerHistograms& histograms);

  // Recompute the bounds from a new global layer histogram along axis().
  // The axis stays fixed: switching it would migrate nearly every particle.
  void rebalance(const Histogram& layer_counts);
  void rebalance(const std::vector<Vec3d>& positions);  // single-process convenience

  int axis() const { return axis_; }
  const std::vector<int>& layer_bounds() const { return bounds_; }         // n_ranks + 1 entries
  double boundary(int r) const { return grid_.face(axis_, bounds_[std::size_t(r)]); }  // lower face of slab r
  const std::vector<std::int64_t>& loads() const { return loads_; }     // particles per rank
  int rank_of_layer(int layer) const { return layer_rank_[std::size_t(layer)]; }

  int n_ranks() const override { return n_ranks_; }
  int owner(const Vec3d& x) const override;
  void ranks_near(const Vec3d& x, double halo_width, int self, std::vector<int>& out) const override;
  std::vector<int> neighbours(int rank) const override;
  double imbalance() const override { return imbalance_; }
  std::string describe() const override;
  OwnerMapHost owner_map() const override;
  const CoarseGrid& grid() const override { return grid_; }

 private:
  CoarseGrid grid_;
  int n_ranks_ = 1;
  int axis_ = 0;
  std::vector<int> bounds_;
  std::vector<int> layer_rank_;  // layer -> owning rank, so owner() is O(1)
  std::vector<std::int64_t> loads_;
  double imbalance_ = 1.0;
};

}  // namespace gs
