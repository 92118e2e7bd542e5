#include "scene/sphere_grid.hpp"

#include <algorithm>
#include <cmath>

#include "core/periodic_box.hpp"  // component

namespace gs {

CellLayout::CellLayout(const Vec3d& lo, const Vec3d& hi, double wished_side, double max_cells) : lo_(lo) {
  h_ = wished_side > 0 ? wished_side : 1.0;
  double n[3];
  for (;;) {  // counted in double: a tiny side over a huge box must not overflow
    for (int a = 0; a < 3; ++a) n[a] = std::max(1.0, std::ceil((component(hi, a) - component(lo, a)) / h_));
    if (n[0] * n[1] * n[2] <= max_cells) break;
    h_ *= 1.1;
  }
  for (int a = 0; a < 3; ++a) n_[a] = int(n[a]);
  inv_h_ = 1.0 / h_;
}

int CellLayout::index(double x, int axis) const {
  // Clamping is monotone, so cells shared by two bounding boxes stay shared.
  const double i = std::floor((x - component(lo_, axis)) * inv_h_);
  return int(std::clamp(i, 0.0, double(n_[axis] - 1)));
}

// ---- SphereGrid ----------------------------------------------------------------

SphereGrid::SphereGrid(const Vec3d& lo, const Vec3d& hi, double wished_side, std::size_t expected)
    : layout_(lo, hi, wished_side, 16.0 * double(expected) + 4096.0), head_(layout_.cells(), -1) {
  spheres_.reserve(expected);
}

void SphereGrid::insert(const Vec3d& c, double r) {
  const auto id = std::int32_t(spheres_.size());
  spheres_.push_back({c, r});
  const int i0 = layout_.index(c.x - r, 0), i1 = layout_.index(c.x + r, 0);
  const int j0 = layout_.index(c.y - r, 1), j1 = layout_.index(c.y + r, 1);
  const int k0 = layout_.index(c.z - r, 2), k1 = layout_.index(c.z + r, 2);
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        std::int32_t& head = head_[layout_.flat(i, j, k)];
        entries_.push_back({id, head});
        head = std::int32_t(entries_.size() - 1);
      }
}

long SphereGrid::overlapping(const Vec3d& c, double r, double tol) const {
  const int i0 = layout_.index(c.x - r, 0), i1 = layout_.index(c.x + r, 0);
  const int j0 = layout_.index(c.y - r, 1), j1 = layout_.index(c.y + r, 1);
  const int k0 = layout_.index(c.z - r, 2), k1 = layout_.index(c.z + r, 2);
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (std::int32_t e = head_[layout_.flat(i, j, k)]; e >= 0; e = entries_[e].next) {
          const Sphere& other = spheres_[entries_[e].sphere];
          const double reach = (r + other.radius) * (1.0 - tol);
          if (norm2(other.centre - c) < reach * reach) return entries_[e].sphere;
        }
  return -1;
}

// ---- TakenCells ----------------------------------------------------------------

TakenCells::TakenCells(const Vec3d& lo, const Vec3d& hi, double wished_side, double max_cells)
    : lo_(lo), hi_(hi), layout_(lo, hi, wished_side, max_cells), bits_((layout_.cells() + 63) / 64, 0) {}

void TakenCells::take_ball(const Vec3d& c, double reach) {
  const double h = layout_.side(), reach2 = reach * reach;
  // Distance from x to the farthest point of [lo, lo + h].
  auto far = [h](double x, double lo) { return std::max(std::abs(x - lo), std::abs(x - lo - h)); };
  const int i0 = layout_.index(c.x - reach, 0), i1 = layout_.index(c.x + reach, 0);
  const int j0 = layout_.index(c.y - reach, 1), j1 = layout_.index(c.y + reach, 1);
  const int k0 = layout_.index(c.z - reach, 2), k1 = layout_.index(c.z + reach, 2);
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j) {
      const Vec3d row = layout_.corner(0, j, k);
      const double fy = far(c.y, row.y), fz = far(c.z, row.z), rest = reach2 - fy * fy - fz * fz;
      if (rest <= 0) continue;
      for (int i = i0; i <= i1; ++i) {
        const double fx = far(c.x, row.x + i * h);
        if (fx * fx < rest) {
          const std::size_t cell = layout_.flat(i, j, k);
          bits_[cell >> 6] |= std::uint64_t(1) << (cell & 63);
        }
      }
    }
}

bool TakenCells::sample(std::mt19937_64& rng, Vec3d& point) const {
  const Vec3d span = hi_ - lo_;
  const double x = uniform01(rng), y = uniform01(rng), z = uniform01(rng);
  point = lo_ + Vec3d(span.x * x, span.y * y, span.z * z);
  const std::size_t cell =
      layout_.flat(layout_.index(point.x, 0), layout_.index(point.y, 1), layout_.index(point.z, 2));
  return !(bits_[cell >> 6] >> (cell & 63) & 1);
}

}  // namespace gs
