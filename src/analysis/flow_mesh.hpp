#pragma once
// Flow through a triangle mesh (docs/MEASUREMENTS.md, "Flow through a mesh"):
// the straight segment between a particle's two sampled centres is tested
// against every triangle. It crosses triangle (a, b, c) when its endpoints lie
// on the two sides of the triangle's plane (front: n . (x - a) >= 0, with
// n = (b - a) x (c - a), the winding's normal) and its line passes through the
// triangle: the three signed volumes of (p, q) with the directed edges
// a->b, b->c, c->a have one sign (Pluecker's test). Each crossing counts +1
// from back to front, -1 from front to back.
//
// Why signed volumes and not a hit point: a volume of edge (u, v) is the exact
// negative of that of (v, u) in floating point, so two triangles that share an
// edge see one value of opposite signs and a path near a shared edge counts in
// exactly one of them. A volume that is exactly zero (a path through an edge
// or a vertex) takes the sign it has for the path shifted by an infinitesimal
// fixed offset, the same for every edge: a path through a vertex counts in the
// one triangle of its fan the shifted path crosses. So a square of two
// triangles counts what a rectangle counts, and a closed surface's net count
// is the change of inside (tests/analysis/test_flow_mesh.cpp).
#include <vector>

#include "core/vec3.hpp"
#include "walls/triangle_mesh.hpp"

namespace gs {

// The crossings of one segment through a surface, in each direction.
struct FlowCrossings {
  int forward = 0, backward = 0;
};

class FlowMeshSurface {
 public:
  explicit FlowMeshSurface(const TriangleMesh& mesh);
  FlowCrossings crossings(const Vec3d& before, const Vec3d& after) const;

 private:
  // Whether the line p->q passes on the positive side of edge (u, v) of the
  // mesh (vertex indices), zero volumes resolved by the indices' order.
  bool positive_side(const Vec3d& p, const Vec3d& q, int u, int v) const;
  int crossing(int t, const Vec3d& p, const Vec3d& q) const;

  TriangleMesh mesh_;
  std::vector<Vec3d> lo_, hi_;  // per triangle: its bounds
  Vec3d mesh_lo_, mesh_hi_;
};

}  // namespace gs
