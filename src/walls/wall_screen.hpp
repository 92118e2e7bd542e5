#pragma once
// A cheap first test of whether a wall can touch a sphere, in the world frame.
// wall_contact() carries the centre into the wall's reference pose (a
// rotation) before it tests anything; in a box of six planes most of those
// tests find no contact, so the force loop screens each wall first with the
// wall's surface already posed. The screen only ever lets a contact through:
// it errs on the side of "may touch" by a slack far above rounding.
#include <cmath>

#include "walls/wall_geometry.hpp"

namespace gs {

struct WallScreen {
  WallKind kind = WallKind::plane;
  Vec3d point;        // the wall's `point` at its current pose
  Vec3d normal;       // its `normal` (plane normal, cylinder axis) at its current pose
  double radius = 0;  // cylinder radius
  double scale = 0;   // |point|_1: sets the slack for rounding far from the origin
};

inline WallScreen wall_screen(const Wall& w) {
  WallScreen s;
  s.kind = w.kind;
  s.point = wall_to_world(w, w.point);
  s.normal = wall_rotate(w, w.normal);
  s.radius = w.radius;
  s.scale = std::fabs(s.point.x) + std::fabs(s.point.y) + std::fabs(s.point.z);
  return s;
}

// False only when the sphere (centre x, radius) is certainly clear of the
// wall: in front of a plane or disk by more than its radius, further than its
// radius from a plate's plane on either side, or nearer a cylinder's axis
// than the cylinder radius less its own. A cone is always let through.
GS_HD GS_INLINE bool wall_may_touch(const WallScreen& s, const Vec3d& x, double radius) {
  const Vec3d v = x - s.point;
  const double slack = 1e-9 * (std::fabs(x.x) + std::fabs(x.y) + std::fabs(x.z) + s.scale + radius);
  if (s.kind == WallKind::cylinder) {
    const double along = dot(v, s.normal);
    const double clear = s.radius - radius - slack;  // largest distance from the axis without contact
    return !(clear > 0 && norm2(v) - along * along < clear * clear);
  }
  if (s.kind == WallKind::cone) return true;  // wall_contact is its only test
  const double h = dot(v, s.normal);
  if (s.kind == WallKind::plate) return std::fabs(h) < radius + slack;  // touched from both sides
  return h < radius + slack;
}

}  // namespace gs
