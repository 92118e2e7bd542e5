#include "walls/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

namespace gs {

namespace {

std::uint64_t bits(double v) {
  v += 0.0;  // -0 -> +0, so that the two zeros are one vertex
  std::uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

std::array<std::uint64_t, 3> key_of(const Vec3d& x) { return {bits(x.x), bits(x.y), bits(x.z)}; }

// Keeps the vertices used by a triangle, in their order, and renumbers.
void drop_unused_vertices(TriangleMesh& mesh) {
  std::vector<std::int32_t> new_index(mesh.vertices.size(), -1);
  for (const TriangleIndices& t : mesh.triangles)
    for (std::int32_t v : t) new_index[v] = 0;
  std::vector<Vec3d> kept;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (new_index[v] == 0) {
      new_index[v] = std::int32_t(kept.size());
      kept.push_back(mesh.vertices[v]);
    }
  for (TriangleIndices& t : mesh.triangles)
    for (std::int32_t& v : t) v = new_index[v];
  mesh.vertices.swap(kept);
}

struct CellKeyHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& k) const {
    return std::size_t(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
  }
};

}  // namespace

TriangleMeshBuilder::TriangleMeshBuilder(std::string name) { mesh_.name = std::move(name); }

std::int32_t TriangleMeshBuilder::vertex(const Vec3d& x) {
  const auto [it, added] = index_.emplace(key_of(x), std::int32_t(mesh_.vertices.size()));
  if (added) mesh_.vertices.push_back(x);
  return it->second;
}

TriangleMesh TriangleMeshBuilder::take() {
  index_.clear();
  return std::move(mesh_);
}

std::size_t weld_vertices(TriangleMesh& mesh, double tolerance) {
  if (!(tolerance >= 0)) throw std::invalid_argument("weld tolerance must be >= 0");
  const std::size_t n = mesh.vertices.size();
  std::vector<std::int32_t> representative(n);
  if (tolerance == 0) {
    std::map<std::array<std::uint64_t, 3>, std::int32_t> first;
    for (std::size_t v = 0; v < n; ++v)
      representative[v] = first.emplace(key_of(mesh.vertices[v]), std::int32_t(v)).first->second;
  } else {
    // Grid of cells of edge `tolerance`: a vertex within the tolerance of a
    // representative is in one of the 27 cells around it.
    std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::int32_t>, CellKeyHash> cells;
    const double inv = 1.0 / tolerance;
    const double tol2 = tolerance * tolerance;
    for (std::size_t v = 0; v < n; ++v) {
      const Vec3d& x = mesh.vertices[v];
      const double f[3] = {x.x * inv, x.y * inv, x.z * inv};
      std::array<std::int64_t, 3> c;
      for (int a = 0; a < 3; ++a) {
        if (!(std::fabs(f[a]) < 1e15))
          throw std::runtime_error("weld tolerance " + std::to_string(tolerance) +
                                   " is too small for coordinates of this size (or a coordinate is not finite)");
        c[a] = std::int64_t(std::floor(f[a]));
      }
      std::int32_t best = std::int32_t(v);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
            if (it == cells.end()) continue;
            for (std::int32_t r : it->second)
              if (r < best && norm2(mesh.vertices[r] - x) <= tol2) best = r;
          }
      representative[v] = best;
      if (best == std::int32_t(v)) cells[c].push_back(best);
    }
  }
  std::size_t merged = 0;
  for (std::size_t v = 0; v < n; ++v) merged += representative[v] != std::int32_t(v);
  for (TriangleIndices& t : mesh.triangles)
    for (std::int32_t& v : t) v = representative[v];
  drop_unused_vertices(mesh);
  return merged;
}

std::string find_mesh_problem(const TriangleMesh& mesh, std::size_t& triangle) {
  triangle = 0;
  if (mesh.triangles.empty()) return "the mesh has no triangles";
  const std::int64_t nv = std::int64_t(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    triangle = t;
    const TriangleIndices& tri = mesh.triangles[t];
    for (std::int32_t v : tri)
      if (v < 0 || v >= nv) return "has vertex index " + std::to_string(v) + " out of range";
    const Vec3d& a = mesh.vertices[tri[0]];
    const Vec3d& b = mesh.vertices[tri[1]];
    const Vec3d& c = mesh.vertices[tri[2]];
    for (const Vec3d* x : {&a, &b, &c})
      if (!std::isfinite(x->x) || !std::isfinite(x->y) || !std::isfinite(x->z))
        return "has a non-finite (NaN or infinite) coordinate";
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
      return "is degenerate (zero area): two of its corners coincide";
    const double longest2 = std::max({norm2(b - a), norm2(c - b), norm2(a - c)});
    if (norm(cross(b - a, c - a)) <= 1e-12 * longest2)
      return "is degenerate (zero area): its corners are collinear";
  }
  return {};
}

void validate_mesh(const TriangleMesh& mesh, const std::string& where) {
  std::size_t t = 0;
  const std::string problem = find_mesh_problem(mesh, t);
  if (problem.empty()) return;
  if (mesh.triangles.empty()) throw std::runtime_error(where + ": " + problem);
  throw std::runtime_error(where + ": triangle " + std::to_string(t) + " " + problem);
}

MeshTopology mesh_topology(const TriangleMesh& mesh) {
  // (lo, hi, forward) per triangle edge; sorting groups the uses of each edge.
  std::vector<std::tuple<std::int32_t, std::int32_t, bool>> uses;
  uses.reserve(3 * mesh.triangles.size());
  for (const TriangleIndices& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[k], b = t[(k + 1) % 3];
      uses.emplace_back(std::min(a, b), std::max(a, b), a < b);
    }
  std::sort(uses.begin(), uses.end());
  MeshTopology topo;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && std::get<0>(uses[j]) == std::get<0>(uses[i]) &&
           std::get<1>(uses[j]) == std::get<1>(uses[i]))
      ++j;
    const std::size_t count = j - i;
    ++topo.edges;
    if (count == 1) ++topo.boundary_edges;
    if (count > 2) ++topo.non_manifold_edges;
    if (count == 2 && std::get<2>(uses[i]) == std::get<2>(uses[i + 1])) ++topo.misoriented_edges;
    i = j;
  }
  return topo;
}

double mesh_volume(const TriangleMesh& mesh) {
  // Relative to the first vertex, which keeps the sum well conditioned far
  // from the origin; the result does not depend on the reference point.
  if (mesh.vertices.empty()) return 0;
  const Vec3d o = mesh.vertices[0];
  double six_v = 0;
  for (const TriangleIndices& t : mesh.triangles)
    six_v += dot(mesh.vertices[t[0]] - o, cross(mesh.vertices[t[1]] - o, mesh.vertices[t[2]] - o));
  return six_v / 6.0;
}

void mesh_bounds(const TriangleMesh& mesh, Vec3d& lo, Vec3d& hi) {
  if (mesh.vertices.empty()) {
    lo = hi = Vec3d();
    return;
  }
  lo = hi = mesh.vertices[0];
  for (const Vec3d& x : mesh.vertices) {
    lo = Vec3d(std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z));
    hi = Vec3d(std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z));
  }
}

void append_mesh(TriangleMesh& a, const TriangleMesh& b) {
  const std::int32_t offset = std::int32_t(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const TriangleIndices& t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace gs
