#pragma once
// How far the walls have moved since the neighbour lists were built: the
// rows of surface slots (engine/surface_rows.hpp) go to the particles a wall
// can reach while no point of any wall near the particles has moved more than
// half the Verlet skin and no wall has been switched on or off, so a build is
// due before either happens (as MeshDrift does for the meshes).
#include <vector>

#include "walls/wall.hpp"

namespace gs {

// A bound on how far any point of the box [lo, hi], carried along with wall
// `from`, moves when the wall takes the pose of `to`: |R_to R_from^T - I|
// (Frobenius, above the largest stretch) times the farthest corner from the
// rotation centre, plus the change of the shift.
double wall_displacement_bound(const Wall& from, const Wall& to, const Vec3d& lo, const Vec3d& hi);

class WallDrift {
 public:
  WallDrift() = default;
  // [lo, hi]: where the centres of the particles stay (the domain, with a margin).
  WallDrift(const Vec3d& lo, const Vec3d& hi) : lo_(lo), hi_(hi) {}
  // The poses the lists are built at.
  void built(const std::vector<Wall>& walls) { built_at_ = walls; }
  // Whether, posed as `walls` are now, some wall was switched on or off or
  // may have moved some point of the box more than `allowed` since the last
  // build (always, before the first).
  bool beyond(const std::vector<Wall>& walls, double allowed) const;

 private:
  Vec3d lo_, hi_;
  std::vector<Wall> built_at_;
};

}  // namespace gs
