#include "analysis/flow_mesh.hpp"

#include <algorithm>

namespace gs {

namespace {

Vec3d min3(const Vec3d& a, const Vec3d& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3d max3(const Vec3d& a, const Vec3d& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

// Two fixed directions, neither along an axis nor in a coordinate plane, for
// the paths through an edge or a vertex (positive_side).
const Vec3d kShiftA{0.5773502691896257, 0.3090169943749474, 0.7548776662466927};
const Vec3d kShiftB{-0.2679491924311227, 0.8660254037844386, 0.4226182617406994};

// Whether the boxes [lo0, hi0] and [lo1, hi1] meet (touching counts).
bool boxes_meet(const Vec3d& lo0, const Vec3d& hi0, const Vec3d& lo1, const Vec3d& hi1) {
  return lo0.x <= hi1.x && lo1.x <= hi0.x && lo0.y <= hi1.y && lo1.y <= hi0.y && lo0.z <= hi1.z && lo1.z <= hi0.z;
}

}  // namespace

FlowMeshSurface::FlowMeshSurface(const TriangleMesh& mesh) : mesh_(mesh) {
  mesh_bounds(mesh_, mesh_lo_, mesh_hi_);
  for (const TriangleIndices& t : mesh_.triangles) {
    const Vec3d &a = mesh_.vertices[t[0]], &b = mesh_.vertices[t[1]], &c = mesh_.vertices[t[2]];
    lo_.push_back(min3(a, min3(b, c)));
    hi_.push_back(max3(a, max3(b, c)));
  }
}

bool FlowMeshSurface::positive_side(const Vec3d& p, const Vec3d& q, int u, int v) const {
  // The signed volume of the tetrahedron (p, q, u, v): swapping u and v
  // negates every rounded operation, so the value is exactly antisymmetric.
  const Vec3d &xu = mesh_.vertices[std::size_t(u)], &xv = mesh_.vertices[std::size_t(v)];
  const double volume = dot(q - p, cross(xu - p, xv - p));
  if (volume != 0) return volume > 0;
  // The line meets the edge's line: decide as for the line shifted by
  // epsilon * shift, whose volume is volume - epsilon (q - p) . (shift x (v - u))
  // to first order; the same shift for every edge, so a path through an
  // edge or a vertex counts in exactly the triangle the shifted path crosses.
  const Vec3d edge = xv - xu;
  for (const Vec3d& shift : {kShiftA, kShiftB}) {
    const double moved = -dot(q - p, cross(shift, edge));
    if (moved != 0) return moved > 0;
  }
  return u < v;
}

int FlowMeshSurface::crossing(int t, const Vec3d& p, const Vec3d& q) const {
  const TriangleIndices& k = mesh_.triangles[std::size_t(t)];
  const Vec3d& a = mesh_.vertices[k[0]];
  const Vec3d n = cross(mesh_.vertices[k[1]] - a, mesh_.vertices[k[2]] - a);
  const bool front_p = dot(n, p - a) >= 0, front_q = dot(n, q - a) >= 0;
  if (front_p == front_q) return 0;
  const bool ab = positive_side(p, q, k[0], k[1]);
  if (positive_side(p, q, k[1], k[2]) != ab || positive_side(p, q, k[2], k[0]) != ab) return 0;
  return front_q ? 1 : -1;
}

FlowCrossings FlowMeshSurface::crossings(const Vec3d& before, const Vec3d& after) const {
  FlowCrossings c;
  const Vec3d lo = min3(before, after), hi = max3(before, after);
  if (!boxes_meet(lo, hi, mesh_lo_, mesh_hi_)) return c;
  for (std::size_t t = 0; t < lo_.size(); ++t) {
    if (!boxes_meet(lo, hi, lo_[t], hi_[t])) continue;
    const int s = crossing(int(t), before, after);
    if (s > 0) ++c.forward;
    if (s < 0) ++c.backward;
  }
  return c;
}

}  // namespace gs
