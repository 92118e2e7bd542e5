#pragma once
#include "core/vec3.hpp"

namespace gs {

enum class WallKind : int {
  plane,    // infinite plane; particles live on the side `normal` points to
  disk,     // plane bounded by a circle of `radius` around `point` (cylinder end caps)
  cylinder, // inside surface of a finite cylinder: base centre `point`, unit axis `normal`
  plate,    // thin flat sheet touched from both sides and at its rims: the plane through
            // `point` across `normal`, within `radius` (may be infinite) of `point`, less a
            // hole centred there (circular or rectangular; walls/sheet_geometry.hpp)
  cone      // thin conical sheet (a hopper), touched from both sides and at its rims:
            // radius `radius` at `point`, `end_radius` at point + length * normal
};

// One analytic wall as the kernels see it. Geometry is given in the wall's
// reference pose (t = 0); the pose at the current time is a rotation about
// `axis_point` followed by a shift, refreshed by the host every step.
struct Wall {
  WallKind kind = WallKind::plane;
  int material = 0;
  Vec3d point;         // plane/disk: a point on it; cylinder: centre of the base circle
  Vec3d normal;        // plane/disk: unit normal into the particle side; cylinder: unit axis
  double radius = 0;   // disk and cylinder radius [m]
  double length = 0;   // cylinder and cone length along the axis [m]
  // plate: the hole's half sizes [m]: {radius, 0} for a circular hole (no hole
  // when 0), {along tangent, across it} for a rectangular one.
  double hole_half[2] = {0, 0};
  Vec3d tangent;          // plate with a rectangular hole: unit in-plane direction of its first side
  double end_radius = 0;  // cone: radius at point + length * normal [m]

  // Prescribed motion: translation at `velocity`, rotation at `angular_velocity`
  // (rad/s, vector along the rotation axis) about `axis_point`.
  Vec3d velocity;
  Vec3d angular_velocity;
  Vec3d axis_point;
  // The motion begins at this time [s]; until then the wall rests in its
  // reference pose (a mixer's impeller waits while the powder settles).
  double motion_start = 0;

  // Current pose: x_world = rotation * (x_ref - axis_point) + axis_point + shift.
  double rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3d shift;
  // Whether the wall acts now (its timeline's active window, walls/timeline.hpp):
  // an inactive wall touches nothing, so its contacts end and their history is released.
  bool active = true;
};

// What a wall contact needs to know about the touching sphere.
struct WallContact {
  double overlap;        // > 0 when in contact [m]
  Vec3d normal;          // unit, from the wall towards the sphere centre
  Vec3d point;           // contact point on the wall surface (world frame)
  Vec3d wall_velocity;   // velocity of the wall surface at `point`
};

}  // namespace gs
