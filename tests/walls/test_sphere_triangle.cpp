// Closest point of a triangle: every one of the 7 regions, checked against the
// construction of the point and against an independent brute-force minimiser
// (dense sampling of the triangle, then a pattern search on the simplex).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "walls/sphere_triangle.hpp"

namespace gs {
namespace {

struct Tri {
  Vec3d a, b, c;
  Vec3d corner(int k) const { return k == 0 ? a : (k == 1 ? b : c); }
  Vec3d at(double u, double v) const { return a + (b - a) * u + (c - a) * v; }
  Vec3d unit_normal() const {
    const Vec3d n = cross(b - a, c - a);
    return n * (1.0 / norm(n));
  }
  // Outward in-plane normal of edge k (corner k to corner k+1).
  Vec3d edge_outward(int k) const {
    const Vec3d m = cross(corner((k + 1) % 3) - corner(k), unit_normal());
    return m * (1.0 / norm(m));
  }
};

// Independent minimiser of |p - x| over the triangle, in barycentric (u, v).
Vec3d brute_force_closest(const Vec3d& p, const Tri& t) {
  auto feasible = [](double& u, double& v) {
    u = std::max(u, 0.0);
    v = std::max(v, 0.0);
    if (u + v > 1) {
      const double s = u + v;
      u /= s;
      v /= s;
    }
  };
  const int n = 200;
  double bu = 0, bv = 0, best = norm2(p - t.a);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double d = norm2(p - t.at(double(i) / n, double(j) / n));
      if (d < best) best = d, bu = double(i) / n, bv = double(j) / n;
    }
  const double dirs[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}, {1, 1}, {-1, -1}};
  for (double step = 1.0 / n; step > 1e-15;) {
    bool moved = false;
    for (const auto& d : dirs) {
      double u = bu + step * d[0], v = bv + step * d[1];
      feasible(u, v);
      const double e = norm2(p - t.at(u, v));
      if (e < best) best = e, bu = u, bv = v, moved = true;
    }
    if (!moved) step *= 0.5;
  }
  return t.at(bu, bv);
}

const Tri kTriangles[] = {
    {{0.1, -0.2, 0.3}, {4.0, 0.5, 0.3}, {1.2, 3.0, -0.4}},  // acute, tilted
    {{0, 0, 0}, {5, 0, 0}, {4.5, 0.8, 0.2}},                // obtuse at c
    {{-1, 2, 7}, {-1.5, 2.2, 7.1}, {-0.7, 2.9, 6.2}},       // small, off the origin
};

void expect_region(const Tri& t, const Vec3d& p, const Vec3d& q, std::uint8_t feature, const char* what) {
  const ClosestPoint r = closest_point_on_triangle(p, t.a, t.b, t.c);
  const double scale = norm(t.b - t.a) + norm(p - t.a);
  EXPECT_EQ(int(r.feature), int(feature)) << what;
  EXPECT_NEAR(norm(r.point - q), 0, 1e-12 * scale) << what;
  EXPECT_NEAR(r.distance, norm(p - q), 1e-12 * scale) << what;
  const Vec3d brute = brute_force_closest(p, t);
  EXPECT_NEAR(norm(r.point - brute), 0, 1e-6 * scale) << what << " (brute force)";
  EXPECT_NEAR(r.distance, norm(p - brute), 1e-10 * scale) << what << " (brute force)";
  EXPECT_LE(r.distance, norm(p - brute) + 1e-14 * scale) << what << " (never worse than brute force)";
}

TEST(ClosestPointOnTriangle, EachOfTheSevenRegions) {
  for (const Tri& t : kTriangles) {
    const Vec3d n = t.unit_normal();
    const double size = norm(t.b - t.a);
    for (double h : {0.7 * size, -0.3 * size, 0.0}) {
      // Face: a point inside, lifted along the normal (either side) or on it.
      const Vec3d q = t.a * 0.3 + t.b * 0.3 + t.c * 0.4;
      if (h != 0) expect_region(t, q + n * h, q, kFace, "face");
      for (int k = 0; k < 3; ++k) {
        // Edge k: out of the edge's mid part along its outward normal, plus lift.
        const Vec3d u = t.corner(k), w = t.corner((k + 1) % 3);
        const Vec3d qe = u + (w - u) * 0.4;
        expect_region(t, qe + t.edge_outward(k) * (0.5 * size) + n * h, qe, std::uint8_t(kEdge0 + k), "edge");
        // Vertex k: inside the cone of the outward normals of its two edges.
        const Vec3d cone = t.edge_outward(k) + t.edge_outward((k + 2) % 3);
        expect_region(t, t.corner(k) + cone * (0.4 * size) + n * h, t.corner(k), std::uint8_t(kVertex0 + k),
                      "vertex");
      }
    }
  }
}

TEST(ClosestPointOnTriangle, RandomPointsMatchBruteForce) {
  std::mt19937_64 rng(7);
  for (const Tri& t : kTriangles) {
    const double size = std::max({norm(t.b - t.a), norm(t.c - t.b), norm(t.a - t.c)});
    const Vec3d centroid = (t.a + t.b + t.c) * (1.0 / 3);
    std::uniform_real_distribution<double> d(-1.5 * size, 1.5 * size);
    int regions[7] = {0, 0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 1000; ++i) {
      const Vec3d p = centroid + Vec3d(d(rng), d(rng), d(rng));
      const ClosestPoint r = closest_point_on_triangle(p, t.a, t.b, t.c);
      const Vec3d brute = brute_force_closest(p, t);
      EXPECT_NEAR(r.distance, norm(p - brute), 1e-10 * size);
      EXPECT_LE(r.distance, norm(p - brute) + 1e-14 * size);
      ++regions[r.feature];
      // The reported point lies on the reported feature.
      if (is_vertex_feature(r.feature)) {
        EXPECT_EQ(norm(r.point - t.corner(r.feature - kVertex0)), 0.0);
      }
      if (is_edge_feature(r.feature)) {
        const int k = r.feature - kEdge0;
        const Vec3d u = t.corner(k), w = t.corner((k + 1) % 3);
        EXPECT_NEAR(norm(cross(r.point - u, w - u)) / norm(w - u), 0, 1e-12 * size);
      }
    }
    for (int f = 0; f < 7; ++f) EXPECT_GT(regions[f], 0) << "region " << f << " never hit";
  }
}

TEST(ClosestPointOnTriangle, ProjectionOnAnEdgeReportsTheEdge) {
  // Exactly above an edge (to the last bit), both triangles of the edge must
  // say "edge", never "face": that is what makes the de-duplication exact.
  const Vec3d a(0, 0, 0), b(1, 0, 0), c(0.3, 1, 0), d(0.6, -1, 0);
  const Vec3d p(0.5, 0, 0.25);
  const ClosestPoint up = closest_point_on_triangle(p, a, b, c);
  const ClosestPoint down = closest_point_on_triangle(p, b, a, d);
  EXPECT_EQ(int(up.feature), int(kEdge0));
  EXPECT_EQ(int(down.feature), int(kEdge0));
  EXPECT_EQ(up.distance, 0.25);
  EXPECT_EQ(down.distance, 0.25);
}

TEST(ClosestPointOnTriangle, PointOnTheTriangle) {
  const Tri& t = kTriangles[0];
  const Vec3d q = t.at(0.2, 0.3);
  const ClosestPoint r = closest_point_on_triangle(q, t.a, t.b, t.c);
  EXPECT_NEAR(r.distance, 0, 1e-15);
  EXPECT_EQ(closest_point_on_triangle(t.b, t.a, t.b, t.c).feature, kVertex1);
}

}  // namespace
}  // namespace gs
