#pragma once
// How far the meshes have moved since the neighbour lists were built: the
// near lists (walls/mesh_near.hpp) hold what a particle can touch while no
// point of any mesh has moved more than half the Verlet skin, so a build is
// due before one would.
#include <vector>

#include "walls/mesh.hpp"

namespace gs {

class MeshDrift {
 public:
  MeshDrift() = default;  // no mesh
  // The ball about each mesh's reference bounds that holds its vertices.
  explicit MeshDrift(const MeshSet& set);
  // The poses the lists are built at.
  void built(const MeshSet& set) { built_at_ = set.pose; }
  // Whether some point of some mesh, posed as `set` is now, may have moved
  // more than `allowed` since the last build (always, before the first).
  bool beyond(const MeshSet& set, double allowed) const;

 private:
  std::vector<Vec3d> centre_;
  std::vector<double> extent_;
  std::vector<MeshPose> built_at_;
};

}  // namespace gs
