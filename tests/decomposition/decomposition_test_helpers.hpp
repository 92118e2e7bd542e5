#pragma once
// Shared helpers for the decomposition tests: point clouds and brute-force
// references that do not reuse the code under test.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "core/vec3.hpp"
#include "decomposition/decomposition.hpp"

namespace gs::test {

inline std::vector<Vec3d> uniform_points(std::size_t n, const Vec3d& lo, const Vec3d& hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3d> p(n);
  for (auto& x : p)
    x = Vec3d(lo.x + (hi.x - lo.x) * u(rng), lo.y + (hi.y - lo.y) * u(rng), lo.z + (hi.z - lo.z) * u(rng));
  return p;
}

// Particles in a ring r in [r_in, r_out] around the z axis (uniform in area), z in [0, height].
inline std::vector<Vec3d> annulus_points(std::size_t n, double r_in, double r_out, double height, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3d> p(n);
  for (auto& x : p) {
    const double r = std::sqrt(r_in * r_in + (r_out * r_out - r_in * r_in) * u(rng));
    const double t = 6.283185307179586 * u(rng);  // 2 pi
    x = Vec3d(r * std::cos(t), r * std::sin(t), height * u(rng));
  }
  return p;
}

inline double box_distance(const Vec3d& a, const Vec3d& b) {
  return std::max({std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.z - b.z)});
}

// Points on a regular m^3 lattice over [lo, hi], faces included.
inline std::vector<Vec3d> lattice(const Vec3d& lo, const Vec3d& hi, int m) {
  std::vector<Vec3d> p;
  p.reserve(std::size_t(m) * m * m);
  const double s = 1.0 / (m - 1);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        p.emplace_back(lo.x + (hi.x - lo.x) * i * s, lo.y + (hi.y - lo.y) * j * s, lo.z + (hi.z - lo.z) * k * s);
  return p;
}

// Owners (other than self) of lattice points within box distance h of x.
inline std::set<int> owners_within(const Decomposition& d, const std::vector<Vec3d>& lat, const Vec3d& x, double h,
                                   int self) {
  std::set<int> out;
  for (const Vec3d& p : lat)
    if (box_distance(p, x) <= h) out.insert(d.owner(p));
  out.erase(self);
  return out;
}

// Query points: random interior points plus points exactly on coarse-cell
// faces and corners, where rounding is most likely to drop a rank.
inline std::vector<Vec3d> query_points(const CoarseGrid& g, std::size_t n_random, unsigned seed) {
  auto q = uniform_points(n_random, Vec3d(g.lo[0], g.lo[1], g.lo[2]), Vec3d(g.hi[0], g.hi[1], g.hi[2]), seed);
  std::mt19937_64 rng(seed + 1);
  for (int i = 0; i < 60; ++i) {
    const int a = int(rng() % std::uint64_t(g.dims[0] + 1)), b = int(rng() % std::uint64_t(g.dims[1] + 1));
    const int c = int(rng() % std::uint64_t(g.dims[2] + 1));
    q.emplace_back(g.face(0, a), g.face(1, b), g.face(2, c));
  }
  return q;
}

// Checks ranks_near against brute force on a lattice of spacing <= s (s no
// larger than a coarse cell): conservative (every owner of a lattice point
// within h is listed) and tight (every listed rank owns a lattice point within
// h + s, the most a lattice can be off; 1% slack absorbs rounding in the
// distances). Returns the number of failures.
inline int check_ranks_near(const Decomposition& d, const std::vector<Vec3d>& lat, double s,
                            const std::vector<Vec3d>& queries, const std::vector<double>& widths) {
  int failures = 0;
  std::vector<int> listed;
  for (const Vec3d& x : queries)
    for (double h : widths) {
      const int self = d.owner(x);
      listed.assign(1, -7);  // sentinel: ranks_near must append, not clear
      d.ranks_near(x, h, self, listed);
      if (listed.front() != -7) ++failures;
      const std::set<int> got(listed.begin() + 1, listed.end());
      if (got.size() + 1 != listed.size() || got.count(self)) ++failures;  // duplicates or self
      const std::set<int> must = owners_within(d, lat, x, h, self);
      const std::set<int> may = owners_within(d, lat, x, h + 1.01 * s, self);
      if (!std::includes(got.begin(), got.end(), must.begin(), must.end())) ++failures;
      if (!std::includes(may.begin(), may.end(), got.begin(), got.end())) ++failures;
    }
  return failures;
}

// Checks neighbours(): symmetric, and covering ranks_near(x, h <= cell_size) for x owned by the rank.
inline int check_neighbours(const Decomposition& d, const std::vector<Vec3d>& queries, double cell_size) {
  int failures = 0;
  for (int a = 0; a < d.n_ranks(); ++a)
    for (int b : d.neighbours(a)) {
      const auto nb = d.neighbours(b);
      if (b == a || std::find(nb.begin(), nb.end(), a) == nb.end()) ++failures;
    }
  std::vector<int> near;
  for (const Vec3d& x : queries) {
    const int self = d.owner(x);
    const auto nb = d.neighbours(self);
    near.clear();
    d.ranks_near(x, cell_size, self, near);
    for (int r : near)
      if (std::find(nb.begin(), nb.end(), r) == nb.end()) ++failures;
  }
  return failures;
}

}  // namespace gs::test
