#pragma once
// The triangle-mesh walls at one output time (docs/OUTPUT.md), so ParaView
// shows the geometry with the particles: meshes_<step>.h5 with /vertices
// (V, 3) fp64 at the current pose, /triangles (T, 3) int32 vertex indices and
// /mesh (T) int32 mesh index, indexed over time by meshes.xdmf.
#include <string>
#include <vector>

#include "walls/mesh.hpp"

namespace gs {

std::string meshes_h5_name(long long step);  // meshes_<step, 10 digits>.h5
void write_meshes_h5(const std::string& path, const MeshSet& meshes, double time, long long step);

struct MeshSeriesEntry {
  double time;
  std::string h5_file;
  std::size_t vertices, triangles;
};
void write_mesh_xdmf(const std::string& path, const std::vector<MeshSeriesEntry>& entries);

}  // namespace gs
