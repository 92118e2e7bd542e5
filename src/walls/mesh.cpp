#include "walls/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>
#include <stdexcept>
#include <tuple>

#include "walls/sphere_triangle.hpp"

namespace gs {

MeshView MeshSet::view() const {
  MeshView v;
  v.vertex = vertex.data();
  v.corners = corners.data();
  v.edges = edges.data();
  v.edge_ends = edge_ends.data();
  v.owned = owned.data();
  v.crease_cos = crease_cos.data();
  v.mesh = mesh.data();
  v.pose = pose.data();
  v.material = material.data();
  v.n_triangles = n_triangles();
  v.n_meshes = n_meshes();
  return v;
}

std::int32_t add_mesh(MeshSet& set, const TriangleMesh& mesh, std::int32_t material, const MeshMotion& motion,
                      double crease_angle_deg) {
  const std::string where = "mesh '" + mesh.name + "'";
  validate_mesh(mesh, where);
  if (!(crease_angle_deg >= 0 && crease_angle_deg < 90))
    throw std::invalid_argument(where + ": crease angle must lie in [0, 90) degrees");
  constexpr std::int64_t kLimit = std::numeric_limits<std::int32_t>::max() / 2;
  if (std::int64_t(set.vertex.size()) + std::int64_t(mesh.vertices.size()) > kLimit ||
      std::int64_t(set.corners.size()) + std::int64_t(mesh.triangles.size()) > kLimit)
    throw std::runtime_error(where + ": too many vertices or triangles in the scene's meshes");

  const std::int32_t id = set.n_meshes();
  const std::int32_t v0 = set.n_vertices();
  const std::int32_t t0 = set.n_triangles();
  if (set.vertex_begin.empty()) set.vertex_begin.push_back(0);
  if (set.triangle_begin.empty()) set.triangle_begin.push_back(0);
  set.names.push_back(mesh.name);
  set.material.push_back(material);
  set.crease_cos.push_back(std::cos(crease_angle_deg * 3.14159265358979323846 / 180));
  set.motion.push_back(motion);
  set.pose.push_back(mesh_pose(motion, 0.0));
  set.reference.insert(set.reference.end(), mesh.vertices.begin(), mesh.vertices.end());
  for (const Vec3d& x : mesh.vertices) set.vertex.push_back(pose_point(set.pose.back(), x));
  set.vertex_begin.push_back(set.n_vertices());

  const std::size_t nt = mesh.triangles.size();
  std::vector<bool> vertex_seen(mesh.vertices.size(), false);
  for (std::size_t t = 0; t < nt; ++t) {
    MeshCorners c;
    std::uint8_t owned = 0;
    for (int k = 0; k < 3; ++k) {
      c.v[k] = v0 + mesh.triangles[t][k];
      if (!vertex_seen[mesh.triangles[t][k]]) {
        vertex_seen[mesh.triangles[t][k]] = true;
        owned |= std::uint8_t(kOwnsVertex0 << k);  // first (lowest-index) user owns the vertex
      }
    }
    set.corners.push_back(c);
    set.edges.push_back(MeshEdges{{-1, -1, -1}});
    set.owned.push_back(owned);
    set.mesh.push_back(id);
  }

  // Edges: (lo, hi, triangle, k) sorted, so the uses of one edge are adjacent
  // and in ascending triangle order; numbering follows (lo, hi).
  std::vector<std::tuple<std::int32_t, std::int32_t, std::int32_t, int>> uses;
  uses.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      uses.emplace_back(std::min(a, b), std::max(a, b), t0 + std::int32_t(t), k);
    }
  std::sort(uses.begin(), uses.end());
  for (std::size_t i = 0; i < uses.size(); ++i) {
    const auto [lo, hi, t, k] = uses[i];
    const bool first = i == 0 || std::get<0>(uses[i - 1]) != lo || std::get<1>(uses[i - 1]) != hi;
    if (first) {
      ++set.n_edges;
      set.owned[t] |= std::uint8_t(kOwnsEdge0 << k);
      set.edge_ends.push_back(EdgeEnds{{v0 + lo, v0 + hi}});
    }
    set.edges[t].e[k] = set.n_edges - 1;
  }
  set.triangle_begin.push_back(set.n_triangles());
  return id;
}

void set_mesh_poses(MeshSet& set, double time) {
  for (std::int32_t m = 0; m < set.n_meshes(); ++m) set.pose[m] = mesh_pose(set.motion[m], time);
}

void move_meshes(MeshSet& set, double time) {
  set_mesh_poses(set, time);
  for (std::int32_t m = 0; m < set.n_meshes(); ++m) {
    pose_vertices(set.pose[m], set.reference.data(), set.vertex.data(), std::size_t(set.vertex_begin[m]),
                  std::size_t(set.vertex_begin[m + 1]));
  }
}

namespace {

// Calls visit(cell) for every cell the triangle is binned in, in ascending
// linear order (z, then y, then x).
template <class Visit>
void for_each_binned_cell(const MeshSet& set, const Vec3d* vertex, std::int32_t t, const CellGrid& grid,
                          const BinningOptions& o, Visit&& visit) {
  const Vec3d& a = vertex[set.corners[t].v[0]];
  const Vec3d& b = vertex[set.corners[t].v[1]];
  const Vec3d& c = vertex[set.corners[t].v[2]];
  const Vec3d lo(std::min({a.x, b.x, c.x}) - o.reach, std::min({a.y, b.y, c.y}) - o.reach,
                 std::min({a.z, b.z, c.z}) - o.reach);
  const Vec3d hi(std::max({a.x, b.x, c.x}) + o.reach, std::max({a.y, b.y, c.y}) + o.reach,
                 std::max({a.z, b.z, c.z}) + o.reach);
  const CellCoord cl = grid.coord(lo), ch = grid.coord(hi);
  // Slack for rounding in the pruning distance: never drop a cell wrongly.
  const double keep = (o.reach + 0.5 * std::sqrt(3.0) * grid.cell_size) * (1 + 1e-9);
  for (int z = cl.z; z <= ch.z; ++z)
    for (int y = cl.y; y <= ch.y; ++y)
      for (int x = cl.x; x <= ch.x; ++x) {
        if (o.prune_by_distance) {
          const Vec3d centre = grid.origin + Vec3d(x + 0.5, y + 0.5, z + 0.5) * grid.cell_size;
          if (closest_point_on_triangle(centre, a, b, c).distance > keep) continue;
        }
        visit(grid.linear({x, y, z}));
      }
}

// The padding of a mesh's grid: a little more than the reach, so that a
// point exactly at it still falls inside.
double grid_margin(double reach) { return reach * (1 + 1e-9) + 1e-12; }

// One grid over the reference vertices of mesh m, inflated by the reach.
CellGrid mesh_grid(const MeshSet& set, std::int32_t m, double cell_size, double reach) {
  Vec3d lo, hi;
  mesh_reference_bounds(set, m, lo, hi);
  const double margin = grid_margin(reach);
  const Vec3d pad(margin, margin, margin);
  return make_cell_grid(lo - pad, hi + pad, cell_size);
}

// Bound on the cells triangle (a, b, c) is binned in (see MeshBinningSize).
double triangle_entries_bound(const Vec3d& a, const Vec3d& b, const Vec3d& c, double h, const BinningOptions& o) {
  // Cells an interval of length L spans: fewer than L / h + 2.
  auto span = [&](double p, double q, double r) {
    return (std::max({p, q, r}) - std::min({p, q, r}) + 2 * o.reach) / h + 2;
  };
  const double box = span(a.x, b.x, c.x) * span(a.y, b.y, c.y) * span(a.z, b.z, c.z);
  if (!o.prune_by_distance) return box;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * h;
  const double rho = (o.reach + half_diagonal) * (1 + 1e-9) + half_diagonal;  // keep + half a diagonal
  const double area = 0.5 * norm(cross(b - a, c - a));
  const double perimeter = norm(b - a) + norm(c - b) + norm(a - c);
  const double pi = 3.14159265358979323846;
  const double dilated = 2 * rho * area + 0.5 * pi * rho * rho * perimeter + 4.0 / 3.0 * pi * rho * rho * rho;
  return std::min(box, dilated / (h * h * h));
}

[[noreturn]] void refuse_binning(const std::string& what) {
  throw std::runtime_error("mesh binning: " + what + "; use larger cells, a coarser mesh, or check the mesh's units");
}

std::string count_text(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g", x);
  return s;
}

}  // namespace

void mesh_reference_bounds(const MeshSet& set, std::int32_t m, Vec3d& lo, Vec3d& hi) {
  lo = Vec3d(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::infinity());
  hi = lo * -1.0;
  for (std::int32_t v = set.vertex_begin[m]; v < set.vertex_begin[m + 1]; ++v) {
    const Vec3d& x = set.reference[v];
    lo = Vec3d(std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z));
    hi = Vec3d(std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z));
  }
}

double MeshBinningSize::total_cells() const { return std::accumulate(cells.begin(), cells.end(), 0.0); }
double MeshBinningSize::total_entries() const { return std::accumulate(entries.begin(), entries.end(), 0.0); }
double MeshBinningSize::bytes() const { return 4.0 * (total_cells() + 1 + total_entries()); }

MeshBinningSize binning_size(const MeshSet& set, double cell_size, const BinningOptions& options) {
  MeshBinningSize size;
  const double margin = grid_margin(options.reach);
  const Vec3d pad(margin, margin, margin);
  for (std::int32_t m = 0; m < set.n_meshes(); ++m) {
    Vec3d lo, hi;
    mesh_reference_bounds(set, m, lo, hi);
    size.cells.push_back(grid_cells(lo - pad, hi + pad, cell_size));
    size.entries.push_back(0);
  }
  for (std::int32_t t = 0; t < set.n_triangles(); ++t) {
    const MeshCorners& c = set.corners[t];
    size.entries[set.mesh[t]] += triangle_entries_bound(set.reference[c.v[0]], set.reference[c.v[1]],
                                                        set.reference[c.v[2]], cell_size, options);
  }
  return size;
}

MeshBins bin_triangles(const MeshSet& set, double cell_size, const BinningOptions& options) {
  if (!(options.reach >= 0)) throw std::invalid_argument("mesh binning reach must be >= 0");
  if (!(cell_size > 0)) throw std::invalid_argument("mesh binning cell size must be positive");
  // Refused before anything is allocated: a mesh in the wrong units would
  // otherwise spend minutes counting and then run out of memory.
  const MeshBinningSize size = binning_size(set, cell_size, options);
  for (std::int32_t m = 0; m < set.n_meshes(); ++m)
    if (!(size.cells[m] <= kMaxGridCells))
      refuse_binning("mesh '" + set.names[m] + "' needs " + count_text(size.cells[m]) + " cells of " +
                     count_text(cell_size) + " m, more than " + count_text(kMaxGridCells));
  if (!(size.total_cells() <= kMaxGridCells))
    refuse_binning("the meshes need " + count_text(size.total_cells()) + " cells together, more than " +
                   count_text(kMaxGridCells));
  if (!(size.total_entries() <= kMaxBinEntries))
    refuse_binning("up to " + count_text(size.total_entries()) +
                   " (cell, triangle) entries would exceed the 32-bit index range");
  MeshBins bins;
  bins.first_cell.push_back(0);
  for (std::int32_t m = 0; m < set.n_meshes(); ++m) {
    bins.grid.push_back(mesh_grid(set, m, cell_size, options.reach));
    bins.first_cell.push_back(bins.first_cell.back() + bins.grid.back().cell_count());
  }
  const std::int64_t cells = bins.first_cell.back();
  bins.cell_begin.assign(std::size_t(cells) + 1, 0);
  // Counting sort: count per cell, prefix sums, then fill in triangle order,
  // which leaves every cell's list ascending.
  auto for_each_entry = [&](auto&& visit) {
    for (std::int32_t t = 0; t < set.n_triangles(); ++t) {
      const std::int32_t m = set.mesh[t];
      for_each_binned_cell(set, set.reference.data(), t, bins.grid[m], options,
                           [&](std::int64_t cell) { visit(t, bins.first_cell[m] + cell); });
    }
  };
  std::int64_t total = 0;
  for_each_entry([&](std::int32_t, std::int64_t cell) {
    ++bins.cell_begin[cell + 1];
    ++total;
  });
  if (total > std::numeric_limits<std::int32_t>::max())
    throw std::runtime_error("mesh binning: " + std::to_string(total) +
                             " (cell, triangle) entries exceed the 32-bit index range; use larger cells or a coarser mesh");
  for (std::int64_t c = 0; c < cells; ++c) bins.cell_begin[c + 1] += bins.cell_begin[c];
  bins.triangles.resize(std::size_t(total));
  std::vector<std::int32_t> fill(bins.cell_begin.begin(), bins.cell_begin.end() - 1);
  for_each_entry([&](std::int32_t t, std::int64_t cell) { bins.triangles[fill[cell]++] = t; });
  return bins;
}

}  // namespace gs
