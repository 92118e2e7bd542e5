#pragma once
// The scene's triangle meshes in a backend's memory, and the per-particle
// loads on them (walls/mesh.hpp has the layout). Topology, reference vertices,
// materials and bins are uploaded once; every step the meshes move, kernels
// pose the vertices from the reference (ForceComputer::set_mesh_pose).
// Empty, and never read by a kernel, when the scene has none.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "backend/device_array.hpp"
#include "walls/mesh.hpp"

namespace gs {

struct DeviceMeshes {
  explicit DeviceMeshes(Backend b)
      : reference(b), vertex(b), corners(b), edges(b), edge_ends(b), owned(b), mesh(b), pose(b), material(b),
        crease_cos(b), bin_grid(b), bin_first_cell(b), cell_begin(b), cell_triangles(b), load(b) {}

  DeviceArray<Vec3d> reference;  // per vertex, reference pose
  DeviceArray<Vec3d> vertex;     // per vertex, current pose
  DeviceArray<MeshCorners> corners;
  DeviceArray<MeshEdges> edges;
  DeviceArray<EdgeEnds> edge_ends;
  DeviceArray<std::uint8_t> owned;
  DeviceArray<std::int32_t> mesh;
  DeviceArray<MeshPose> pose;
  DeviceArray<std::int32_t> material;
  DeviceArray<double> crease_cos;
  DeviceArray<CellGrid> bin_grid;
  DeviceArray<std::int64_t> bin_first_cell;
  DeviceArray<std::int32_t> cell_begin, cell_triangles;
  DeviceArray<MeshLoad> load;  // per particle x mesh
  std::int32_t n_triangles = 0, n_meshes = 0;
  // The most triangles a particle's near list can hold (walls/mesh_near.hpp:
  // one cell of each mesh): the longest cell list of each mesh, summed.
  std::int64_t near_bound = 0;

  void set(const MeshSet& s) {
    n_triangles = s.n_triangles();
    n_meshes = s.n_meshes();
    corners.from_host(s.corners);
    edges.from_host(s.edges);
    edge_ends.from_host(s.edge_ends);
    owned.from_host(s.owned);
    mesh.from_host(s.mesh);
    material.from_host(s.material);
    crease_cos.from_host(s.crease_cos);
    reference.from_host(s.reference);
    vertex.from_host(s.vertex);
    pose.from_host(s.pose);
  }
  void set_bins(const MeshBins& b) {
    bin_grid.from_host(b.grid);
    bin_first_cell.from_host(b.first_cell);
    cell_begin.from_host(b.cell_begin);
    cell_triangles.from_host(b.triangles);
    near_bound = 0;
    for (std::size_t m = 0; m + 1 < b.first_cell.size(); ++m) {
      std::int64_t longest = 0;
      for (std::int64_t c = b.first_cell[m]; c < b.first_cell[m + 1]; ++c)
        longest = std::max<std::int64_t>(longest, b.cell_begin[std::size_t(c) + 1] - b.cell_begin[std::size_t(c)]);
      near_bound += longest;
    }
  }
  // Room for the loads of n particles (only when there are meshes).
  void reserve(std::size_t n) {
    if (n_triangles > 0) load.resize(n * std::size_t(n_meshes));
  }

  MeshView view() const {
    MeshView v;
    if (n_triangles == 0) return v;
    v.vertex = vertex.data();
    v.corners = corners.data();
    v.edges = edges.data();
    v.edge_ends = edge_ends.data();
    v.owned = owned.data();
    v.mesh = mesh.data();
    v.pose = pose.data();
    v.material = material.data();
    v.crease_cos = crease_cos.data();
    v.n_triangles = n_triangles;
    v.n_meshes = n_meshes;
    v.bin_grid = bin_grid.data();
    v.bin_first_cell = bin_first_cell.data();
    v.cell_begin = cell_begin.data();
    v.cell_triangles = cell_triangles.data();
    return v;
  }
  MeshLoad* loads() { return n_triangles > 0 ? load.data() : nullptr; }

  std::size_t bytes() const {
    return reference.bytes() + vertex.bytes() + corners.bytes() + edges.bytes() + edge_ends.bytes() +
           owned.bytes() + mesh.bytes() + pose.bytes() + material.bytes() + crease_cos.bytes() + bin_grid.bytes() +
           bin_first_cell.bytes() + cell_begin.bytes() + cell_triangles.bytes() + load.bytes();
  }
};

}  // namespace gs
