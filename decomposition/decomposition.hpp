#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "coarse_grid.hpp"
#include "core/owner_map.hpp"
#include "core/vec3.hpp"

namespace gs {

// Who owns which region of space. The domain [lo, hi] is covered by a uniform
// grid of coarse cells of edge >= cell_size (the interaction range); ownership
// is defined per coarse cell so that every rank agrees exactly (integer cell
// coordinates computed identically on every rank, see CoarseGrid).
//
// A rank's owned region is the union of its coarse cells, where cells on the
// domain boundary extend outwards to infinity (owner() clamps outside points
// to the nearest cell). This layer knows nothing about transport or physics.
class Decomposition {
 public:
  virtual ~Decomposition() = default;

  virtual int n_ranks() const = 0;

  // Rank owning point x (points outside the domain are clamped to the nearest cell).
  virtual int owner(const Vec3d& x) const = 0;

  // Appends to out every rank other than `self` whose owned region has a point
  // within box (L-infinity) distance halo_width of x, i.e. that meets the
  // closed cube [x - h, x + h]^3; each such rank is appended once per call and
  // nothing already in out is touched. Box distance <= Euclidean distance, so
  // this is a superset of the ranks within Euclidean distance h: it never
  // misses a rank that needs x as a ghost. Exact up to the rounding of
  // x +- h: a rank whose nearest point is a fraction of an ulp beyond h may be
  // listed, one within h never is missed. x may be any point (its owner need
  // not be self). halo_width >= 0; cost grows with (halo_width / cell edge)^3.
  virtual void ranks_near(const Vec3d& x, double halo_width, int self, std::vector<int>& out) const = 0;

  // Ranks that can exchange halos with `rank`, sorted ascending, without
  // `rank`: every rank owning a cell that shares a face, edge or corner with
  // one of rank's cells. Because cell edges are >= cell_size, this contains
  // ranks_near(x, h, rank) for every x owned by rank and h <= cell_size.
  // Symmetric: a is in neighbours(b) iff b is in neighbours(a).
  virtual std::vector<int> neighbours(int rank) const = 0;

  // max / mean particles per rank at the last (re)partition (1 with no particles).
  virtual double imbalance() const = 0;

  // One line for the run log, e.g. "slabs along z: 4 ranks, imbalance 1.02".
  virtual std::string describe() const = 0;

  // owner() and ranks_near() as a table the backends' routing kernels read
  // (they classify particles on the device, so positions never go to the host).
  virtual OwnerMapHost owner_map() const = 0;

  // The coarse grid ownership is defined on; callers histogram their local
  // particles on it (cell_histogram / layer_histogram) before an all-reduce.
  virtual const CoarseGrid& grid() const = 0;
};

// max / mean of per-rank particle counts; 1 when there are no particles.
inline double load_imbalance(const std::vector<std::int64_t>& loads) {
  std::int64_t total = 0, heaviest = 0;
  for (std::int64_t l : loads) {
    total += l;
    heaviest = std::max(heaviest, l);
  }
  return total == 0 ? 1.0 : double(heaviest) * double(loads.size()) / double(total);
}

}  // namespace gs
