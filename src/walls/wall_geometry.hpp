#pragma once
#include "core/hd.hpp"
#include "core/vec3.hpp"
#include "walls/sheet_geometry.hpp"
#include "walls/wall.hpp"

namespace gs {

// Wall::rotation is stored row-major: rotation[3 * i + j] = R_ij.

// R * v: a direction of the reference pose seen in the current pose.
GS_HD GS_INLINE Vec3d wall_rotate(const Wall& w, const Vec3d& v) {
  const double* R = w.rotation;
  return Vec3d(R[0] * v.x + R[1] * v.y + R[2] * v.z,
               R[3] * v.x + R[4] * v.y + R[5] * v.z,
               R[6] * v.x + R[7] * v.y + R[8] * v.z);
}

// R^T * v: R is orthonormal, so its transpose undoes the rotation without an inverse.
GS_HD GS_INLINE Vec3d wall_unrotate(const Wall& w, const Vec3d& v) {
  const double* R = w.rotation;
  return Vec3d(R[0] * v.x + R[3] * v.y + R[6] * v.z,
               R[1] * v.x + R[4] * v.y + R[7] * v.z,
               R[2] * v.x + R[5] * v.y + R[8] * v.z);
}

// x_world = R (x_ref - axis_point) + axis_point + shift.
GS_HD GS_INLINE Vec3d wall_to_world(const Wall& w, const Vec3d& x_ref) {
  return wall_rotate(w, x_ref - w.axis_point) + w.axis_point + w.shift;
}

// Inverse of wall_to_world: where a world point sits relative to the wall's
// reference geometry, so the geometry itself never has to be moved.
GS_HD GS_INLINE Vec3d wall_to_reference(const Wall& w, const Vec3d& x_world) {
  return wall_unrotate(w, x_world - w.axis_point - w.shift) + w.axis_point;
}

// Contact of a sphere (centre x, radius) with wall w at its current pose.
// Returns true and fills c only when the overlap is strictly positive, and
// never for a wall that is not active now.
//
// Every kind also accepts a centre that has slipped behind the surface by less
// than its radius (overlap between radius and 2 radius), so a fast particle
// that overshoots within one step is pushed back rather than lost. A centre
// further behind is treated as being on the far side: no contact, instead of
// an enormous spurious overlap.
//
//  plane:    overlap = radius - d, d = signed distance of the centre along `normal`.
//  disk:     as plane, but only while the centre projects inside the disk
//            radius; the rim edge is not a contact in this version.
//  cylinder: inside surface; only while the axial coordinate of the centre is
//            in [0, length] (the ends are closed by disks if needed);
//            overlap = radius - (R - rho), rho = distance from the axis; the
//            normal points towards the axis. A centre exactly on the axis has
//            no defined normal and gives no contact.
//  plate, cone: thin sheets, touched from both sides and at their rims
//            (walls/sheet_geometry.hpp): overlap = radius - |x - q|, q the
//            nearest point of the sheet; a centre in the sheet gives no
//            contact. No slipped-behind rule: a centre that crosses the sheet
//            within a step is on its other side.
GS_HD GS_INLINE bool wall_contact(const Wall& w, const Vec3d& x, double radius, WallContact& c) {
  if (!w.active) return false;
  const Vec3d xr = wall_to_reference(w, x);
  Vec3d normal_ref;
  Vec3d point_ref;
  double overlap = 0;

  if (w.kind == WallKind::cylinder) {
    const Vec3d a = xr - w.point;
    const double s = dot(a, w.normal);
    if (s < 0 || s > w.length) return false;
    const Vec3d radial = a - s * w.normal;
    const double rho = norm(radial);
    const double d = w.radius - rho;  // distance of the centre in front of the wall
    overlap = radius - d;
    if (overlap <= 0 || d <= -radius || rho <= 0) return false;
    const Vec3d outward = radial * (1.0 / rho);
    normal_ref = -outward;
    point_ref = w.point + s * w.normal + w.radius * outward;
  } else if (w.kind == WallKind::plate || w.kind == WallKind::cone) {
    const Vec3d q = sheet_nearest(w, xr);  // relative to w.point
    const Vec3d d = (xr - w.point) - q;
    const double distance = norm(d);
    overlap = radius - distance;
    if (overlap <= 0 || !(distance > 0)) return false;
    normal_ref = d * (1.0 / distance);
    point_ref = w.point + q;
  } else {  // plane or disk
    const double d = dot(xr - w.point, w.normal);
    overlap = radius - d;
    if (overlap <= 0 || d <= -radius) return false;
    point_ref = xr - d * w.normal;  // foot of the perpendicular from the centre
    if (w.kind == WallKind::disk && norm2(point_ref - w.point) > w.radius * w.radius) return false;
    normal_ref = w.normal;
  }

  c.overlap = overlap;
  c.normal = wall_rotate(w, normal_ref);
  c.point = wall_to_world(w, point_ref);
  // Rigid-body velocity of the wall material at the contact point; the
  // rotation centre has moved with the shift.
  c.wall_velocity = w.velocity + cross(w.angular_velocity, c.point - (w.axis_point + w.shift));
  return true;
}

// Whether a sphere (centre x, radius) could touch wall w as wall_contact
// decides once its centre has moved by at most `reach` relative to the wall
// (in the wall's reference frame): false only when it certainly could not.
// The contact's region of centres, widened by reach: within radius + reach of
// a plane, disk, plate or cone, and of a cylinder's mantle; a disk's or a
// cylinder's bounds (its radius, its length) widened by reach.
GS_HD GS_INLINE bool wall_within_reach(const Wall& w, const Vec3d& x, double radius, double reach) {
  if (!w.active) return false;
  const Vec3d xr = wall_to_reference(w, x);
  const double band = radius + reach;
  if (w.kind == WallKind::cylinder) {
    const Vec3d a = xr - w.point;
    const double s = dot(a, w.normal);
    if (s < -reach || s > w.length + reach) return false;
    const double d = w.radius - norm(a - s * w.normal);
    return d < band && d > -band;
  }
  if (w.kind == WallKind::plate || w.kind == WallKind::cone) return norm((xr - w.point) - sheet_nearest(w, xr)) < band;
  const double d = dot(xr - w.point, w.normal);  // plane or disk
  if (!(d < band && d > -band)) return false;
  if (w.kind != WallKind::disk) return true;
  const double rim = w.radius + reach;
  return norm2(xr - d * w.normal - w.point) < rim * rim;
}

}  // namespace gs
