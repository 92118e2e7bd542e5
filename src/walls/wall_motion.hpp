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

}  // namespace gs
