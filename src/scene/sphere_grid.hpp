#pragma once
// Uniform grid behind the particle generators: overlap queries among many
// spheres of mixed sizes.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "core/vec3.hpp"

namespace gs {

// Uniform in [0, 1). Written out rather than std::uniform_real_distribution,
// whose output differs between standard libraries: a seed must give the same
// packing everywhere.
inline double uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

// Cells of side h over the box [lo, lo + n h]; the side is grown from the wished
// one until at most `max_cells` cells are needed, bounding the memory.
class CellLayout {
 public:
  CellLayout(const Vec3d& lo, const Vec3d& hi, double wished_side, double max_cells);
  std::size_t cells() const { return std::size_t(n_[0]) * n_[1] * n_[2]; }
  double side() const { return h_; }
  int n(int axis) const { return n_[axis]; }
  // Cell along one axis holding coordinate x, clamped to the grid.
  int index(double x, int axis) const;
  std::size_t flat(int i, int j, int k) const { return (std::size_t(k) * n_[1] + j) * n_[0] + i; }
  Vec3d corner(int i, int j, int k) const { return lo_ + h_ * Vec3d(i, j, k); }

 private:
  Vec3d lo_;
  double h_ = 1, inv_h_ = 1;
  int n_[3] = {1, 1, 1};
};

// Spheres filed in every cell their bounding box touches: two overlapping
// spheres always share a cell, so a query visits only the cells of its own
// bounding box, whatever the size ratio. Cells are lists threaded through
// small entries (no per-cell allocations; a sphere has ~8 entries, so entries
// hold an index rather than the sphere, which keeps 1e6 spheres under 100 MB).
class SphereGrid {
 public:
  SphereGrid(const Vec3d& lo, const Vec3d& hi, double wished_side, std::size_t expected_spheres);
  void insert(const Vec3d& c, double r);
  // Insertion index of a stored sphere overlapping (c, r) by more than `tol`
  // times the sum of the radii, or -1.
  long overlapping(const Vec3d& c, double r, double tol) const;

 private:
  struct Sphere {
    Vec3d centre;
    double radius;
  };
  struct Entry {
    std::int32_t sphere, next;
  };
  CellLayout layout_;
  std::vector<Sphere> spheres_;
  std::vector<std::int32_t> head_;
  std::vector<Entry> entries_;
};

// Cells of a fine grid known to be unable to hold the centre of any further
// sphere. Random sequential addition spends most trials in taken space when
// the fill gets dense; one bit look-up rejects most of those trials before
// the costly overlap query. Trials stay uniform over the free space: a taken
// cell holds no admissible centre, so skipping it removes nothing.
class TakenCells {
 public:
  TakenCells(const Vec3d& lo, const Vec3d& hi, double wished_side, double max_cells);
  // Marks every cell whose points all lie closer than `reach` to c.
  void take_ball(const Vec3d& c, double reach);
  // A uniform point of the grid's box; false when it lies in a taken cell.
  bool sample(std::mt19937_64& rng, Vec3d& point) const;

 private:
  Vec3d lo_, hi_;
  CellLayout layout_;
  std::vector<std::uint64_t> bits_;
};

}  // namespace gs
