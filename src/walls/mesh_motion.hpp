#pragma once
// Prescribed rigid motion of a triangle mesh (an impeller turning at a given
// rpm, a translating plate): the same model as the analytic walls
// (walls/wall_motion.hpp). The pose at time t is computed from the absolute
// time and applied to the reference vertices, never accumulated step by step,
// so the mesh does not drift and a restart reproduces it exactly.
#include <cstddef>

#include "core/hd.hpp"
#include "core/vec3.hpp"
#include "walls/timeline.hpp"

namespace gs {

struct MeshMotion {
  Vec3d velocity;          // translation [m/s]
  Vec3d angular_velocity;  // [rad/s], along the rotation axis (right-hand rule)
  Vec3d axis_point;        // a point of the rotation axis in the reference pose [m]
  double start = 0;        // the motion begins at this time [s]; at rest before
  Timeline timeline;       // active window, tables, oscillation (walls/timeline.hpp)
};

// Rotation about the axis through `axis_point` along `axis_direction` (any
// non-zero length) at `rpm` revolutions per minute (sign: right-hand rule
// about the direction), plus an optional translation.
MeshMotion rotation_at_rpm(const Vec3d& axis_point, const Vec3d& axis_direction, double rpm,
                           const Vec3d& velocity = {});

// The pose of a mesh at one instant and its rigid-body velocity field:
// x_world = R (x_ref - axis_point) + axis_point + shift.
struct MeshPose {
  double rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major, R[3 i + j] = R_ij
  Vec3d shift;
  Vec3d axis_point;  // reference pose
  Vec3d velocity;
  Vec3d angular_velocity;
  bool active = true;  // the mesh acts now (its timeline's active window); else it touches nothing
};

// Pose at absolute time `time` (Rodrigues rotation by |omega| t about omega,
// shift = velocity t, t counted from the motion's start, zero velocities
// before it; or the timeline's tables and oscillation), by the same code as
// the analytic walls (wall_at).
MeshPose mesh_pose(const MeshMotion& motion, double time);

GS_HD GS_INLINE Vec3d pose_rotate(const MeshPose& p, const Vec3d& v) {
  const double* R = p.rotation;
  return Vec3d(R[0] * v.x + R[1] * v.y + R[2] * v.z, R[3] * v.x + R[4] * v.y + R[5] * v.z,
               R[6] * v.x + R[7] * v.y + R[8] * v.z);
}

// Where the material point at x_ref (reference pose) is now.
GS_HD GS_INLINE Vec3d pose_point(const MeshPose& p, const Vec3d& x_ref) {
  return pose_rotate(p, x_ref - p.axis_point) + p.axis_point + p.shift;
}

// The inverse of pose_point: where the world point x sits in the reference pose.
GS_HD GS_INLINE Vec3d pose_reference_point(const MeshPose& p, const Vec3d& x) {
  const double* R = p.rotation;
  const Vec3d d = x - p.axis_point - p.shift;
  return Vec3d(R[0] * d.x + R[3] * d.y + R[6] * d.z, R[1] * d.x + R[4] * d.y + R[7] * d.z,
               R[2] * d.x + R[5] * d.y + R[8] * d.z) +
         p.axis_point;
}

// Velocity of the mesh material at the world point x (e.g. a contact point):
// v + omega x (x - c), c = the rotation centre where it is now.
GS_HD GS_INLINE Vec3d mesh_point_velocity(const MeshPose& p, const Vec3d& x) {
  return p.velocity + cross(p.angular_velocity, x - (p.axis_point + p.shift));
}

// A bound on how far any point of a mesh has moved from pose `from` to pose
// `to`, the mesh's reference vertices lying within `extent` of `centre`:
// with x = R y + b (y = x_ref - centre, b = pose_point(p, centre)), a point
// moves by (R_to - R_from) y + (b_to - b_from), and the spectral norm of
// the difference of two rotations is its Frobenius norm over sqrt(2) (2
// sin(theta / 2) for the angle theta between them): a point at `extent`
// across the axis of a pure rotation attains the bound.
double mesh_displacement_bound(const MeshPose& from, const MeshPose& to, const Vec3d& centre, double extent);

// Sets current[k] = pose_point(pose, reference[k]) for k in [begin, end);
// one functor, run by a host loop here and by Exec::parallel_for on a device.
// Item 0 also stores the pose where the force kernel reads it (`pose_out`,
// when not null): one launch per mesh and step, and no copy from the host,
// which would wait for the device every step.
struct PoseVertices {
  MeshPose pose;
  const Vec3d* reference;
  Vec3d* current;
  std::size_t begin;
  MeshPose* pose_out = nullptr;
  GS_HD void operator()(std::size_t k) const {
    if (k == 0 && pose_out) *pose_out = pose;
    current[begin + k] = pose_point(pose, reference[begin + k]);
  }
};

void pose_vertices(const MeshPose& pose, const Vec3d* reference, Vec3d* current, std::size_t begin,
                   std::size_t end);

}  // namespace gs
