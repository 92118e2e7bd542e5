#pragma once
// What a wall or a mesh does over time beyond a constant motion
// (docs/SCENES.md, `active` and `motion`): the window in which it acts, a
// piecewise-linear table of velocity or angular velocity against time, and a
// sinusoidal oscillation. Host data: the pose they give is computed on the
// host from the absolute time (walls/wall_motion.hpp) and handed to the
// kernels, so nothing accumulates and a restart poses the wall bit for bit.
#include <limits>
#include <vector>

#include "core/vec3.hpp"

namespace gs {

// A piecewise-linear rate (velocity [m/s] or angular velocity [rad/s]) of the
// motion time tau: value[k] at time[k], linear between, value.back() after
// the last time. time[0] = 0 and the times increase strictly.
// integral[k] is the rate's integral from 0 to time[k]: trapezoids summed
// once, in table order, when the table is made.
struct RateTable {
  std::vector<double> time;
  std::vector<Vec3d> value;
  std::vector<Vec3d> integral;
  bool empty() const { return time.empty(); }
};

// Throws std::invalid_argument when the sizes differ, the table is empty,
// time[0] != 0 or the times do not increase strictly (message names the index).
RateTable make_rate_table(std::vector<double> time, std::vector<Vec3d> value);
// The rate at tau >= 0.
Vec3d rate_at(const RateTable& t, double tau);
// Its exact integral from 0 to tau >= 0: the trapezoids before tau's segment
// plus h (v_k + s h / 2) within it (h = tau - time[k], s the segment's slope).
Vec3d integral_to(const RateTable& t, double tau);

// Displacement amplitude * sin(2 pi frequency tau + phase) along the
// amplitude's direction; its velocity is the derivative.
struct Oscillation {
  Vec3d amplitude;        // direction times amplitude [m]
  double frequency = 0;   // [Hz]
  double phase = 0;       // [rad]
  bool none() const { return frequency == 0 || norm2(amplitude) == 0; }
};
Vec3d oscillation_displacement(const Oscillation& o, double tau);
Vec3d oscillation_velocity(const Oscillation& o, double tau);

// A wall or mesh acts for from <= t < until (absolute time); outside, it
// exerts no force and its contacts end (their history is released).
struct ActiveWindow {
  double from = 0;
  double until = std::numeric_limits<double>::infinity();
  bool contains(double t) const { return t >= from && t < until; }
  bool always() const { return from <= 0 && until == std::numeric_limits<double>::infinity(); }
};

struct Timeline {
  ActiveWindow active;
  RateTable velocity;          // [m/s] against the motion time; replaces the constant velocity
  RateTable angular_velocity;  // [rad/s], all along one axis; replaces the constant angular velocity
  Oscillation oscillation;     // added to the translation
  // Nothing beyond a constant motion: the wall poses as before timelines existed.
  bool none() const { return active.always() && velocity.empty() && angular_velocity.empty() && oscillation.none(); }
};

// The timeline of wall k: `timelines` holds one per wall, or none at all (a
// scene built in code).
inline const Timeline& timeline_of(const std::vector<Timeline>& timelines, std::size_t k) {
  static const Timeline kNone;
  return k < timelines.size() ? timelines[k] : kNone;
}

}  // namespace gs
