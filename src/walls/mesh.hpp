#pragma once
// Triangle-mesh walls laid out for the kernels: flat arrays over all meshes of
// a scene (a MeshSet on the host, a MeshView of plain pointers in a kernel),
// and the binning of triangles into cell grids that move with their mesh, in
// CSR form. Vertices are never shared between meshes, so every edge and vertex
// belongs to one mesh. See docs/MESHES.md.
#include <cstdint>
#include <string>
#include <vector>

#include "core/hd.hpp"
#include "core/vec3.hpp"
#include "neighbor/cell_grid.hpp"
#include "walls/mesh_motion.hpp"
#include "walls/triangle_mesh.hpp"

namespace gs {

// Corner k of a triangle is corners.v[k]; edge k joins corners k and (k+1)%3.
struct MeshCorners {
  std::int32_t v[3];  // vertex indices into the set's vertex arrays
};
struct MeshEdges {
  std::int32_t e[3];  // edge indices, numbered over the whole set
};
struct EdgeEnds {
  std::int32_t v[2];  // the edge's vertices, lower index first
};

// Bits of MeshSet::owned: the triangle owns edge k (bit k) or corner k (bit
// 3 + k). Each edge and each vertex is owned by exactly one triangle, the
// lowest-index one that uses it.
constexpr std::uint8_t kOwnsEdge0 = 1u << 0;
constexpr std::uint8_t kOwnsVertex0 = 1u << 3;

// What a kernel reads. All arrays are indexed by triangle unless noted.
struct MeshView {
  const Vec3d* vertex = nullptr;             // per vertex, current pose [m]
  const MeshCorners* corners = nullptr;
  const MeshEdges* edges = nullptr;
  const EdgeEnds* edge_ends = nullptr;       // per edge
  const std::uint8_t* owned = nullptr;
  const std::int32_t* mesh = nullptr;        // mesh id of the triangle
  const MeshPose* pose = nullptr;            // per mesh: current pose and velocity field
  const std::int32_t* material = nullptr;    // per mesh: material index
  const double* crease_cos = nullptr;        // per mesh: cos(crease angle), rule F of sphere_triangle.hpp
  std::int32_t n_triangles = 0;
  std::int32_t n_meshes = 0;
  // Binning (MeshBins): one grid per mesh, in its reference pose.
  const CellGrid* bin_grid = nullptr;         // per mesh
  const std::int64_t* bin_first_cell = nullptr;  // per mesh: its cells' first index in cell_begin
  const std::int32_t* cell_begin = nullptr;   // per cell + 1: range in cell_triangles
  const std::int32_t* cell_triangles = nullptr;

  // Triangles of mesh m that may touch a sphere centred at the world point
  // x, ascending; an empty range where none can (x outside the mesh's grid).
  GS_HD void cell_range(std::int32_t m, const Vec3d& x, std::int32_t& begin, std::int32_t& end) const {
    const Vec3d r = pose_reference_point(pose[m], x);
    const CellGrid& g = bin_grid[m];
    const double f[3] = {(r.x - g.origin.x) * g.inverse_edge[0], (r.y - g.origin.y) * g.inverse_edge[1],
                         (r.z - g.origin.z) * g.inverse_edge[2]};
    begin = end = 0;
    for (int a = 0; a < 3; ++a)
      if (!(f[a] >= 0 && f[a] < double(g.dims[a]))) return;
    const std::int64_t cell = bin_first_cell[m] + g.linear({int(f[0]), int(f[1]), int(f[2])});
    begin = cell_begin[cell];
    end = cell_begin[cell + 1];
  }
  GS_HD bool has_vertex(std::int32_t t, std::int32_t v) const {
    const MeshCorners& c = corners[t];
    return c.v[0] == v || c.v[1] == v || c.v[2] == v;
  }
  GS_HD bool has_edge(std::int32_t t, std::int32_t e) const {
    const MeshEdges& c = edges[t];
    return c.e[0] == e || c.e[1] == e || c.e[2] == e;
  }
  GS_HD bool shares_vertex(std::int32_t t, std::int32_t u) const {
    const MeshCorners& c = corners[u];
    return has_vertex(t, c.v[0]) || has_vertex(t, c.v[1]) || has_vertex(t, c.v[2]);
  }
};

// Load that particles put on one mesh: the force and the torque about the
// mesh's rotation centre where it is now (axis_point + shift of its pose).
struct MeshLoad {
  Vec3d force;   // [N]
  Vec3d torque;  // [N m]
};

// Host storage of all meshes of a scene, concatenated in input order.
struct MeshSet {
  std::vector<std::string> names;             // per mesh
  std::vector<std::int32_t> vertex_begin;     // per mesh + 1
  std::vector<std::int32_t> triangle_begin;   // per mesh + 1
  std::vector<std::int32_t> material;         // per mesh
  std::vector<double> crease_cos;             // per mesh: cos(crease angle)
  std::vector<MeshMotion> motion;             // per mesh
  std::vector<MeshPose> pose;                 // per mesh, at the time of the last set_mesh_poses or move_meshes
  std::vector<Vec3d> reference;               // per vertex, reference pose (t = 0)
  std::vector<Vec3d> vertex;                  // per vertex, current pose
  std::vector<MeshCorners> corners;           // per triangle
  std::vector<MeshEdges> edges;
  std::vector<EdgeEnds> edge_ends;            // per edge
  std::vector<std::uint8_t> owned;
  std::vector<std::int32_t> mesh;
  std::int32_t n_edges = 0;

  std::int32_t n_meshes() const { return std::int32_t(names.size()); }
  std::int32_t n_triangles() const { return std::int32_t(corners.size()); }
  std::int32_t n_vertices() const { return std::int32_t(vertex.size()); }
  // Host view (host pointers), without bins unless given.
  MeshView view() const;
};

// Appends a validated mesh (see validate_mesh) with its material and motion;
// numbers its edges and computes feature ownership. Two faces of the mesh
// touched at once whose normals differ by less than `crease_angle_deg` count
// as one curved surface (a tessellated cylinder seen from inside), two faces
// at a larger angle as a corner (rule F of walls/sphere_triangle.hpp).
// Returns its mesh id.
constexpr double kDefaultCreaseAngleDeg = 30;
std::int32_t add_mesh(MeshSet& set, const TriangleMesh& mesh, std::int32_t material = 0,
                      const MeshMotion& motion = {}, double crease_angle_deg = kDefaultCreaseAngleDeg);

// Moves every mesh to its pose at absolute time `time` (from the reference
// vertices; nothing accumulates).
void move_meshes(MeshSet& set, double time);
// Only the poses at `time` (a run's device poses the vertices itself; the
// host's are needed for output alone).
void set_mesh_poses(MeshSet& set, double time);

// Triangles per cell, CSR, of one grid per mesh laid over the mesh in its
// reference pose. A rigidly moving mesh is binned once and never again: a
// particle is looked up at its position carried back into the reference
// pose (MeshView::cell_range). The triangles of cell c of mesh m are
// triangles[cell_begin[k] .. cell_begin[k + 1]), k = first_cell[m] + c,
// ascending, so a kernel visits them in one canonical order.
struct MeshBins {
  std::vector<CellGrid> grid;              // per mesh
  std::vector<std::int64_t> first_cell;    // per mesh + 1
  std::vector<std::int32_t> cell_begin;    // first_cell.back() + 1
  std::vector<std::int32_t> triangles;
};

struct BinningOptions {
  // A triangle is listed in every cell that its axis-aligned bounding box,
  // inflated by `reach` on all sides, overlaps. Use reach >= the largest
  // particle radius. A mesh's grid covers its bounding box inflated by reach,
  // so every point within reach of a triangle lies inside it.
  double reach = 0;
  // Also drop the cells whose centre is further than reach + the cell's
  // half-diagonal from the triangle: still conservative for every point inside
  // the grid, much shorter lists for large slanted triangles (impeller blades).
  bool prune_by_distance = true;
};

// Relative room on a near list's reach (walls/mesh_near.hpp), and so on the
// bins', for the rounding of distances and poses: 1e-9 m for 1 mm spheres.
constexpr double kMeshNearSlack = 1e-6;

// The options a run bins with in cells of `cell_size` (the largest diameter
// and the Verlet skin `skin`, or more): the reach of the near lists of the
// largest sphere, its radius plus the skin (half a cell and half the skin)
// and their slack, with room for the rounding of a position carried into the
// mesh's frame.
inline BinningOptions run_binning(double cell_size, double skin) {
  return {0.5 * (cell_size + skin) * (1 + kMeshNearSlack) * (1 + 1e-9), true};
}

// Most (cell, triangle) entries a binning may hold: cell_begin is 32-bit.
constexpr double kMaxBinEntries = 2147483647.0;

// What bin_triangles would build, bounded from above before anything is
// allocated (in double, so that a mesh in the wrong units gives a huge number
// instead of an overflow). A triangle's entries are at most the cells its
// inflated bounding box spans; with pruning also at most the cells of edge h
// that fit into the triangle dilated by rho = keep + sqrt(3)/2 h (every kept
// cell lies inside it): by Steiner's formula for a flat triangle of area A
// and perimeter P, (2 rho A + pi/2 rho^2 P + 4/3 pi rho^3) / h^3.
struct MeshBinningSize {
  std::vector<double> cells;    // per mesh: cells of its grid
  std::vector<double> entries;  // per mesh: bound on its (cell, triangle) entries
  double total_cells() const;
  double total_entries() const;
  double bytes() const;  // cell_begin and the triangle lists, 4 bytes an entry
};
MeshBinningSize binning_size(const MeshSet& set, double cell_size, const BinningOptions& options);

// Axis-aligned bounds of mesh m in its reference pose.
void mesh_reference_bounds(const MeshSet& set, std::int32_t m, Vec3d& lo, Vec3d& hi);

// Bins the triangles of `set` in their reference pose, in cells of edge
// `cell_size` (the particle grid's: one cell per sphere diameter or more).
// Throws before allocating when a mesh's grid exceeds kMaxGridCells cells or
// the bound of binning_size exceeds kMaxBinEntries entries.
MeshBins bin_triangles(const MeshSet& set, double cell_size, const BinningOptions& options);

// Attaches bins to a view (host pointers).
inline MeshView with_bins(MeshView v, const MeshBins& bins) {
  v.bin_grid = bins.grid.data();
  v.bin_first_cell = bins.first_cell.data();
  v.cell_begin = bins.cell_begin.data();
  v.cell_triangles = bins.triangles.data();
  return v;
}

}  // namespace gs
