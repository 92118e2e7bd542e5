#pragma once
// Helpers shared by the mesh tests: small meshes built in code and the
// contacts of a sphere collected on the host.
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "walls/mesh.hpp"
#include "walls/sphere_triangle.hpp"
#include "walls/triangle_mesh.hpp"

namespace gs::test {

// Contacts of the sphere (x, radius) with every triangle of the set (the list
// holds all triangles, as a cell list with an unbounded reach would).
inline std::vector<MeshContact> all_contacts(const MeshSet& set, const Vec3d& x, double radius) {
  std::vector<std::int32_t> list(std::size_t(set.n_triangles()));
  std::iota(list.begin(), list.end(), 0);
  std::vector<MeshContact> out;
  auto collect = [&](const MeshContact& c) { out.push_back(c); };
  for_each_mesh_contact_in(set.view(), list.data(), std::int32_t(list.size()), x, radius, collect);
  return out;
}

inline MeshSet single_mesh_set(const TriangleMesh& mesh) {
  MeshSet set;
  add_mesh(set, mesh);
  return set;
}

// Row-major rotation about a unit axis by `angle` (Rodrigues).
struct Rotation {
  double R[9];
  Rotation(Vec3d k, double angle) {
    k = k * (1.0 / norm(k));
    const double c = std::cos(angle), s = std::sin(angle), v = 1 - c;
    const double r[9] = {c + v * k.x * k.x,       v * k.x * k.y - s * k.z, v * k.x * k.z + s * k.y,
                         v * k.y * k.x + s * k.z, c + v * k.y * k.y,       v * k.y * k.z - s * k.x,
                         v * k.z * k.x - s * k.y, v * k.z * k.y + s * k.x, c + v * k.z * k.z};
    for (int i = 0; i < 9; ++i) R[i] = r[i];
  }
  Vec3d operator()(const Vec3d& x) const {
    return Vec3d(R[0] * x.x + R[1] * x.y + R[2] * x.z, R[3] * x.x + R[4] * x.y + R[5] * x.z,
                 R[6] * x.x + R[7] * x.y + R[8] * x.z);
  }
};

// A flat square [0, n h]^2 at z = 0 in its own frame, tessellated into n x n
// cells split along alternating diagonals, interior vertices jittered in the
// plane by up to `jitter` h (so valences and angles vary), then placed in the
// world by x -> rotation(x) + shift. `local` keeps the in-plane positions.
struct FlatSquare {
  TriangleMesh mesh;
  std::vector<Vec3d> local;  // per vertex, in the square's frame (z = 0)
  Vec3d normal;              // world
  Vec3d origin;              // world position of the local origin
  Rotation rotation{Vec3d(0, 0, 1), 0};
  Vec3d to_world(const Vec3d& l) const { return rotation(l) + origin; }
};

inline FlatSquare make_flat_square(int n, double h, double jitter, const Rotation& rotation, const Vec3d& shift,
                                   unsigned seed) {
  FlatSquare sq;
  sq.rotation = rotation;
  sq.origin = shift;
  sq.normal = rotation(Vec3d(0, 0, 1));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * h, jitter * h);
  auto id = [&](int i, int j) { return std::int32_t(j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool interior = i > 0 && j > 0 && i < n && j < n;
      Vec3d l(i * h, j * h, 0);
      if (interior) l += Vec3d(u(rng), u(rng), 0);
      sq.local.push_back(l);
      sq.mesh.vertices.push_back(sq.to_world(l));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        sq.mesh.triangles.push_back({a, b, c});
        sq.mesh.triangles.push_back({a, c, d});
      } else {
        sq.mesh.triangles.push_back({a, b, d});
        sq.mesh.triangles.push_back({b, c, d});
      }
    }
  sq.mesh.name = "flat square";
  return sq;
}

}  // namespace gs::test
