#include "slab_decomposition.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "slab_cuts.hpp"

namespace gs {
namespace {

const char* axis_name(int a) { return a == 0 ? "x" : (a == 1 ? "y" : "z"); }

void check_histogram(const CoarseGrid& grid, int axis, const Histogram& h) {
  if (h.size() != std::size_t(grid.dims[axis]))
    throw std::invalid_argument(std::string("SlabDecomposition: histogram along ") + axis_name(axis) + " has " +
                                std::to_string(h.size()) + " layers, grid has " + std::to_string(grid.dims[axis]));
}

void check_thick_enough(const CoarseGrid& grid, int n_ranks, int axis) {
  if (grid.dims[axis] >= n_ranks) return;
  std::ostringstream msg;
  msg << "SlabDecomposition: domain too thin for " << n_ranks << " ranks along " << axis_name(axis) << ": only "
      << grid.dims[axis] << " coarse layer(s) of edge " << grid.edge[axis]
      << " fit and each slab needs at least one (edge >= cell size); use fewer ranks or another axis";
  throw std::runtime_error(msg.str());
}

// Length of the particles' bounding box along the histogram's axis, in whole layers.
double occupied_extent(const Histogram& h, double edge) {
  std::size_t first = h.size(), last = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (h[i] == 0) continue;
    first = std::min(first, i);
    last = i;
  }
  return first == h.size() ? 0.0 : double(last - first + 1) * edge;
}

}  // namespace

SlabDecomposition::SlabDecomposition(const CoarseGrid& grid, int n_ranks, int axis, const Histogram& layer_counts)
    : grid_(grid), n_ranks_(n_ranks), axis_(axis) {
  if (n_ranks < 1) throw std::invalid_argument("SlabDecomposition: n_ranks must be >= 1");
  if (axis < 0 || axis > 2) throw std::invalid_argument("SlabDecomposition: axis must be 0, 1 or 2 here");
  check_thick_enough(grid, n_ranks, axis);
  rebalance(layer_counts);
}

SlabDecomposition SlabDecomposition::from_histograms(const CoarseGrid& grid, int n_ranks, int axis,
                                                     const LayerHistograms& histograms) {
  if (axis < -1 || axis > 2) throw std::invalid_argument("SlabDecomposition: axis must be -1 (auto), 0, 1 or 2");
  const int a = axis == -1 ? pick_axis(grid, n_ranks, histograms) : axis;
  return SlabDecomposition(grid, n_ranks, a, histograms[std::size_t(a)]);
}

SlabDecomposition SlabDecomposition::from_positions(const Vec3d& lo, const Vec3d& hi, double cell_size,
                                                    int n_ranks, int axis, const std::vector<Vec3d>& positions) {
  const CoarseGrid grid = CoarseGrid::make(lo, hi, cell_size);
  if (axis >= 0 && axis <= 2) return SlabDecomposition(grid, n_ranks, axis, layer_histogram(grid, axis, positions));
  return from_histograms(grid, n_ranks, axis, layer_histograms(grid, positions));
}

int SlabDecomposition::pick_axis(const CoarseGrid& grid, int n_ranks, const LayerHistograms& histograms) {
  int best = -1;
  double best_occupied = -1, best_domain = -1;
  for (int a = 0; a < 3; ++a) {
    check_histogram(grid, a, histograms[std::size_t(a)]);
    if (grid.dims[a] < n_ranks) continue;
    const double occupied = occupied_extent(histograms[std::size_t(a)], grid.edge[a]);
    const double domain = grid.hi[a] - grid.lo[a];
    if (occupied > best_occupied || (occupied == best_occupied && domain > best_domain)) {
      best = a;
      best_occupied = occupied;
      best_domain = domain;
    }
  }
  if (best >= 0) return best;
  std::ostringstream msg;
  msg << "SlabDecomposition: domain too thin for " << n_ranks << " ranks along every axis (coarse layers x/y/z = "
      << grid.dims[0] << "/" << grid.dims[1] << "/" << grid.dims[2] << "); use fewer ranks";
  throw std::runtime_error(msg.str());
}

void SlabDecomposition::rebalance(const Histogram& layer_counts) {
  check_histogram(grid_, axis_, layer_counts);
  bounds_ = balanced_cuts(layer_counts, n_ranks_);
  layer_rank_.assign(layer_counts.size(), 0);
  loads_.assign(std::size_t(n_ranks_), 0);
  for (int r = 0; r < n_ranks_; ++r) {
    for (int l = bounds_[std::size_t(r)]; l < bounds_[std::size_t(r) + 1]; ++l) {
      layer_rank_[std::size_t(l)] = r;
      loads_[std::size_t(r)] += layer_counts[std::size_t(l)];
    }
  }
  imbalance_ = load_imbalance(loads_);
}

void SlabDecomposition::rebalance(const std::vector<Vec3d>& positions) {
  rebalance(layer_histogram(grid_, axis_, positions));
}

int SlabDecomposition::owner(const Vec3d& x) const {
  return rank_of_layer(grid_.coord(axis_, component(x, axis_)));
}

void SlabDecomposition::ranks_near(const Vec3d& x, double halo_width, int self, std::vector<int>& out) const {
  std::array<int, 3> first{}, last{};
  grid_.cells_near(x, halo_width, first, last);
  // Slabs are contiguous and ordered, so the ranks in range are too.
  const int r_first = rank_of_layer(first[std::size_t(axis_)]);
  const int r_last = rank_of_layer(last[std::size_t(axis_)]);
  for (int r = r_first; r <= r_last; ++r)
    if (r != self) out.push_back(r);
}

// One entry per layer along the axis: the other axes do not change the owner.
OwnerMapHost SlabDecomposition::owner_map() const {
  std::array<std::int64_t, 3> stride{0, 0, 0};
  stride[std::size_t(axis_)] = 1;
  return {grid_.owner_map_shape(stride), layer_rank_};
}

std::vector<int> SlabDecomposition::neighbours(int rank) const {
  if (rank < 0 || rank >= n_ranks_) throw std::out_of_range("SlabDecomposition::neighbours: rank out of range");
  std::vector<int> out;
  if (rank > 0) out.push_back(rank - 1);
  if (rank + 1 < n_ranks_) out.push_back(rank + 1);
  return out;
}

std::string SlabDecomposition::describe() const {
  std::ostringstream s;
  s << "slabs along " << axis_name(axis_) << ": " << n_ranks_ << " ranks, imbalance " << std::fixed
    << std::setprecision(2) << imbalance_ << std::defaultfloat << std::setprecision(4) << " ("
    << grid_.dims[axis_] << " layers of " << grid_.edge[axis_] << ")";
  return s.str();
}

}  // namespace gs
