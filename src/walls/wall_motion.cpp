#include "walls/wall_motion.hpp"

#include <cmath>

namespace gs {

void rotation_about(double* R, const Vec3d& k, double angle) {
  // Rodrigues: R = cos(t) I + sin(t) [k]x + (1 - cos(t)) k k^T.
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double v = 1.0 - c;
  R[0] = c + v * k.x * k.x;        R[1] = v * k.x * k.y - s * k.z;  R[2] = v * k.x * k.z + s * k.y;
  R[3] = v * k.y * k.x + s * k.z;  R[4] = c + v * k.y * k.y;        R[5] = v * k.y * k.z - s * k.x;
  R[6] = v * k.z * k.x - s * k.y;  R[7] = v * k.z * k.y + s * k.x;  R[8] = c + v * k.z * k.z;
}

void update_wall_pose(Wall& w, double time) {
  w.shift = w.velocity * time;

  double* R = w.rotation;  // row-major, R[3 * i + j] = R_ij
  const double omega = norm(w.angular_velocity);
  if (omega == 0) {
    for (int i = 0; i < 9; ++i) R[i] = (i % 4 == 0) ? 1.0 : 0.0;
    return;
  }
  rotation_about(R, w.angular_velocity * (1.0 / omega), omega * time);
}

Wall wall_at(const Wall& prescribed, const Timeline& timeline, double time) {
  Wall w = prescribed;
  const double tau = motion_time(time, w.motion_start);
  update_wall_pose(w, tau);
  // Each term only where the timeline has it: a wall without one poses
  // exactly as before timelines existed.
  if (!timeline.velocity.empty()) {
    w.shift += integral_to(timeline.velocity, tau);
    w.velocity += rate_at(timeline.velocity, tau);
  }
  if (!timeline.oscillation.none()) {
    w.shift += oscillation_displacement(timeline.oscillation, tau);
    w.velocity += oscillation_velocity(timeline.oscillation, tau);
  }
  if (!timeline.angular_velocity.empty()) {
    const Vec3d theta = integral_to(timeline.angular_velocity, tau);
    const double angle = norm(theta);
    if (angle > 0) rotation_about(w.rotation, theta * (1.0 / angle), angle);
    w.angular_velocity += rate_at(timeline.angular_velocity, tau);
  }
  if (time < w.motion_start) {
    w.velocity = Vec3d();
    w.angular_velocity = Vec3d();
  }
  w.active = timeline.active.contains(time);
  return w;
}

}  // namespace gs
