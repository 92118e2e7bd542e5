#include "walls/mesh_motion.hpp"

#include <cmath>
#include <stdexcept>

#include "walls/wall_motion.hpp"

namespace gs {

MeshMotion rotation_at_rpm(const Vec3d& axis_point, const Vec3d& axis_direction, double rpm, const Vec3d& velocity) {
  const double length = norm(axis_direction);
  if (!(length > 0) || !std::isfinite(length)) throw std::invalid_argument("rotation axis must be a non-zero vector");
  if (!std::isfinite(rpm)) throw std::invalid_argument("rpm must be finite");
  constexpr double kTwoPi = 6.283185307179586476925;
  MeshMotion m;
  m.angular_velocity = axis_direction * (rpm * kTwoPi / 60.0 / length);
  m.axis_point = axis_point;
  m.velocity = velocity;
  return m;
}

MeshPose mesh_pose(const MeshMotion& motion, double time) {
  // The analytic walls' pose update, reused through a Wall carrying only the motion.
  Wall prescribed;
  prescribed.velocity = motion.velocity;
  prescribed.angular_velocity = motion.angular_velocity;
  prescribed.axis_point = motion.axis_point;
  prescribed.motion_start = motion.start;
  const Wall w = wall_at(prescribed, motion.timeline, time);
  MeshPose p;
  for (int i = 0; i < 9; ++i) p.rotation[i] = w.rotation[i];
  p.shift = w.shift;
  p.axis_point = motion.axis_point;
  p.velocity = w.velocity;
  p.angular_velocity = w.angular_velocity;
  p.active = w.active;
  return p;
}

void pose_vertices(const MeshPose& pose, const Vec3d* reference, Vec3d* current, std::size_t begin, std::size_t end) {
  const PoseVertices f{pose, reference, current, begin};
  for (std::size_t k = 0; k < end - begin; ++k) f(k);
}

double mesh_displacement_bound(const MeshPose& from, const MeshPose& to, const Vec3d& centre, double extent) {
  // The spectral norm of R_to - R_from from the differences themselves:
  // sqrt(3 - trace(R_from^T R_to)), its equal, cancels at small angles.
  double frobenius2 = 0;
  for (int k = 0; k < 9; ++k) frobenius2 += (to.rotation[k] - from.rotation[k]) * (to.rotation[k] - from.rotation[k]);
  const double turn = std::sqrt(0.5 * frobenius2);
  return turn * extent + norm(pose_point(to, centre) - pose_point(from, centre));
}

}  // namespace gs
