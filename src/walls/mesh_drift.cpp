#include "walls/mesh_drift.hpp"

#include <algorithm>

namespace gs {

MeshDrift::MeshDrift(const MeshSet& set) {
  for (std::int32_t m = 0; m < set.n_meshes(); ++m) {
    Vec3d lo, hi;
    mesh_reference_bounds(set, m, lo, hi);
    const Vec3d centre = (lo + hi) * 0.5;
    double extent = 0;
    for (std::int32_t v = set.vertex_begin[m]; v < set.vertex_begin[m + 1]; ++v)
      extent = std::max(extent, norm(set.reference[v] - centre));
    centre_.push_back(centre);
    extent_.push_back(extent);
  }
}

bool MeshDrift::beyond(const MeshSet& set, double allowed) const {
  if (built_at_.size() != set.pose.size()) return true;
  for (std::size_t m = 0; m < built_at_.size(); ++m)
    if (!(mesh_displacement_bound(built_at_[m], set.pose[m], centre_[m], extent_[m]) <= allowed)) return true;
  return false;
}

}  // namespace gs
