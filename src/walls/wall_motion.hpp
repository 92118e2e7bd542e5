#pragma once
#include "walls/timeline.hpp"
#include "walls/wall.hpp"

namespace gs {

// Sets w.rotation and w.shift to the pose at absolute time `time` under the
// wall's constant prescribed motion: a rotation by |angular_velocity| * time
// about the axis angular_velocity / |angular_velocity| through axis_point
// (identity when angular_velocity is zero), and shift = velocity * time.
// The pose is recomputed from the absolute time rather than accumulated step by
// step, so it does not drift and is identical after a restart.
void update_wall_pose(Wall& w, double time);

// Sets R (row-major) to the rotation by `angle` about the unit vector k (Rodrigues).
void rotation_about(double* R, const Vec3d& k, double angle);

// Time the motion has run at `time`, for a motion that begins at `start`.
inline double motion_time(double time, double start) { return time > start ? time - start : 0.0; }

// The prescribed wall as it is at `time`, with the motion time
// tau = motion_time(time, w.motion_start):
//  shift    = velocity tau, or the integral of the timeline's velocity table
//             to tau, plus the oscillation's displacement at tau;
//  rotation = by |angular_velocity| tau about angular_velocity, or by the
//             integral Theta of the angular velocity table (by |Theta| about
//             Theta / |Theta|, one fixed axis);
//  velocity and angular_velocity: their current values (the table's, plus the
//             oscillation's velocity), zero while the motion has not begun,
//             so the velocity of the wall at a contact point is the time
//             derivative of its pose;
//  active   = whether `time` lies in the timeline's active window.
Wall wall_at(const Wall& prescribed, const Timeline& timeline, double time);
inline Wall wall_at(const Wall& prescribed, double time) { return wall_at(prescribed, Timeline{}, time); }

}  // namespace gs
