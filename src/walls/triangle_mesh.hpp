#pragma once
// A triangle mesh on the host, as read from an STL file or made by a
// generator: shared vertices and triangles as vertex index triples. The
// winding gives the orientation (right-hand rule: counter-clockwise seen from
// outside), as in STL. The device layout built from it is in walls/mesh.hpp.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace gs {

using TriangleIndices = std::array<std::int32_t, 3>;

struct TriangleMesh {
  std::string name;               // solid name (ASCII STL) or file stem
  std::vector<Vec3d> vertices;    // [m]
  std::vector<TriangleIndices> triangles;
};

// Appends one triangle given by its corner positions, sharing vertices that
// are bitwise equal (after -0 -> +0) with vertices added before by this
// builder; the mesh-wide tolerance weld is weld_vertices().
class TriangleMeshBuilder {
 public:
  explicit TriangleMeshBuilder(std::string name = {});
  std::int32_t vertex(const Vec3d& x);  // index of x, added if new
  void triangle(std::int32_t a, std::int32_t b, std::int32_t c) { mesh_.triangles.push_back({a, b, c}); }
  void triangle(const Vec3d& a, const Vec3d& b, const Vec3d& c) { triangle(vertex(a), vertex(b), vertex(c)); }
  // Quad a b c d (counter-clockwise from outside) as triangles (a b c), (a c d).
  void quad(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  TriangleMesh take();

 private:
  TriangleMesh mesh_;
  std::map<std::array<std::uint64_t, 3>, std::int32_t> index_;  // coordinate bits -> vertex
};

// Merges vertices closer than `tolerance` (> 0; 0: only bitwise-equal ones)
// into the first of them in index order, renumbers triangles and drops
// vertices no triangle uses. Deterministic: the result depends only on the
// input order. Returns the number of vertices merged away.
std::size_t weld_vertices(TriangleMesh& mesh, double tolerance);

// The first problem of the mesh, or "" when it has none: no triangles, a
// vertex index out of range, a non-finite (NaN or infinite) coordinate, or a
// degenerate triangle (two equal corners, or area <= 5e-13 x its longest edge
// squared, i.e. collinear corners). `triangle` receives the index (from 0, in
// input order) of the offending triangle.
std::string find_mesh_problem(const TriangleMesh& mesh, std::size_t& triangle);

// Throws std::runtime_error("<where>: triangle <i> ...") on the first problem
// find_mesh_problem reports. `where` is usually the file name.
void validate_mesh(const TriangleMesh& mesh, const std::string& where);

// Edges of the mesh and how they are shared.
struct MeshTopology {
  std::size_t edges = 0;
  std::size_t boundary_edges = 0;      // used by one triangle
  std::size_t non_manifold_edges = 0;  // used by three or more
  std::size_t misoriented_edges = 0;   // two triangles traverse it in the same direction
  bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0; }
  bool consistently_oriented() const { return misoriented_edges == 0; }
};
MeshTopology mesh_topology(const TriangleMesh& mesh);

// Enclosed volume by the divergence theorem, sum over triangles of
// a . (b x c) / 6: positive for a closed mesh whose normals point outwards.
// For several closed shells it is the sum of their volumes.
double mesh_volume(const TriangleMesh& mesh);

// Axis-aligned bounds of the vertices.
void mesh_bounds(const TriangleMesh& mesh, Vec3d& lo, Vec3d& hi);

// Appends b's vertices and triangles to a (no welding across the two).
void append_mesh(TriangleMesh& a, const TriangleMesh& b);

}  // namespace gs
