#pragma once
// Contact geometry of the thin walls that particles meet from either side and
// at their edges: a plate (a plane with a circular or rectangular hole, bounded
// or not by an outer circle: an orifice plate, an annular disk) and a cone or
// frustum (a hopper). Each is a surface S; the contact of a sphere is with the
// point q of S nearest its centre x: distance d = |x - q|, normal (x - q) / d,
// overlap radius - d. On the flat of a plate that is the plane's contact, from
// either side; near a rim it is the distance to the rim circle or rectangle,
// with the normal from the nearest rim point. All in the wall's reference
// pose (the caller carries the centre there).
#include <cmath>

#include "core/hd.hpp"
#include "core/vec3.hpp"
#include "walls/wall.hpp"

namespace gs {

// Two unit vectors across the unit vector n, a fixed choice for each n.
GS_HD GS_INLINE void sheet_basis(const Vec3d& n, Vec3d& e1, Vec3d& e2) {
  const Vec3d pick = std::fabs(n.x) < 0.5 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  e1 = cross(n, pick);
  e1 = e1 * (1.0 / norm(e1));
  e2 = cross(n, e1);
}

// The point of the plate's solid region nearest the in-plane vector v (from
// the plate's centre, v across its normal): v itself on the solid, else the
// nearest point of the hole's rim or of the outer circle.
GS_HD GS_INLINE Vec3d plate_nearest(const Wall& w, const Vec3d& v) {
  Vec3d q = v;
  if (w.hole_half[1] > 0) {  // rectangular hole, sides along `tangent` and normal x tangent
    const Vec3d e2 = cross(w.normal, w.tangent);
    const double u = dot(v, w.tangent), t = dot(v, e2);
    const double a = w.hole_half[0], b = w.hole_half[1];
    if (std::fabs(u) < a && std::fabs(t) < b) {  // over the hole: to the nearest side
      if (a - std::fabs(u) <= b - std::fabs(t)) q = v + (std::copysign(a, u) - u) * w.tangent;
      else q = v + (std::copysign(b, t) - t) * e2;
    }
  } else {  // circular hole of radius hole_half[0] (zero: none)
    const double rho = norm(v), r = w.hole_half[0];
    if (rho < r) {
      if (rho > 0) {
        q = v * (r / rho);
      } else {  // the centre of the hole: every rim point is as near; take a fixed one
        Vec3d e1, e2;
        sheet_basis(w.normal, e1, e2);
        q = r * e1;
      }
    }
  }
  const double rho = norm(q);
  if (rho > w.radius) q = q * (w.radius / rho);  // beyond the outer circle (radius may be infinite)
  return q;
}

// The point of the cone's surface nearest x_ref, relative to the base centre
// `point`: in the half-plane through the axis and x, the nearest point of the
// generatrix from (0, radius) to (length, end_radius) (its ends are the rim circles).
GS_HD GS_INLINE Vec3d cone_nearest(const Wall& w, const Vec3d& a) {
  const double s = dot(a, w.normal);
  const Vec3d radial = a - s * w.normal;
  const double rho = norm(radial);
  Vec3d e;
  if (rho > 0) {
    e = radial * (1.0 / rho);
  } else {  // on the axis: every meridian is as near; take a fixed one
    Vec3d e2;
    sheet_basis(w.normal, e, e2);
  }
  const double ds = w.length, dr = w.end_radius - w.radius;
  double t = ((s * ds) + (rho - w.radius) * dr) / (ds * ds + dr * dr);
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return (t * ds) * w.normal + (w.radius + t * dr) * e;
}

// Nearest point of the thin wall w (plate or cone) to the reference-pose
// point x_ref, relative to w.point.
GS_HD GS_INLINE Vec3d sheet_nearest(const Wall& w, const Vec3d& x_ref) {
  const Vec3d a = x_ref - w.point;
  if (w.kind == WallKind::cone) return cone_nearest(w, a);
  const double h = dot(a, w.normal);
  return plate_nearest(w, a - h * w.normal);
}

}  // namespace gs
