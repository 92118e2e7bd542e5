#pragma once
// An analytic wall of a kind at its reference pose, for the wall tests.
#include "walls/wall.hpp"

namespace gs {

inline Wall make_wall(WallKind kind, Vec3d point, Vec3d normal, double radius = 0, double length = 0) {
  Wall w;
  w.kind = kind;
  w.point = point;
  w.normal = normal * (1.0 / norm(normal));
  w.radius = radius;
  w.length = length;
  return w;
}

}  // namespace gs
