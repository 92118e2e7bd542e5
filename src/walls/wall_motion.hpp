#pragma once
#include "walls/wall.hpp"

namespace gs {

// Sets w.rotation and w.shift to the pose at absolute time `time` under the
// wall's constant prescribed motion: a rotation by |angular_velocity| * time
// about the axis angular_velocity / |angular_velocity| through axis_point
// (identity when angular_velocity is zero), and shift = velocity * time.
// The pose is recomputed from the absolute time rather than accumulated step by
// step, so it does not drift and is identical after a restart.
void update_wall_pose(Wall& w, double time);

// Time the motion has run at `time`, for a motion that begins at `start`.
inline double motion_time(double time, double start) { return time > start ? time - start : 0.0; }

// The prescribed wall as it is at `time`: posed after motion_time(time,
// w.motion_start), with zero velocities while its motion has not begun.
Wall wall_at(const Wall& prescribed, double time);

}  // namespace gs
