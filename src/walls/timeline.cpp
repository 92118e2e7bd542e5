#include "walls/timeline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gs {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

// Index of the segment that holds tau: the last k with time[k] <= tau.
std::size_t segment_of(const RateTable& t, double tau) {
  const auto it = std::upper_bound(t.time.begin(), t.time.end(), tau);
  return it == t.time.begin() ? 0 : std::size_t(it - t.time.begin()) - 1;
}

// Slope of segment k; zero past the last time (the last value holds).
Vec3d slope_of(const RateTable& t, std::size_t k) {
  if (k + 1 >= t.time.size()) return Vec3d();
  return (t.value[k + 1] - t.value[k]) * (1.0 / (t.time[k + 1] - t.time[k]));
}

}  // namespace

RateTable make_rate_table(std::vector<double> time, std::vector<Vec3d> value) {
  if (time.empty()) throw std::invalid_argument("a table needs at least one time");
  if (time.size() != value.size())
    throw std::invalid_argument(std::to_string(time.size()) + " times but " + std::to_string(value.size()) +
                                " values");
  if (time[0] != 0) throw std::invalid_argument("the first time must be 0 (the start of the motion)");
  for (std::size_t k = 1; k < time.size(); ++k)
    if (!(time[k] > time[k - 1]))
      throw std::invalid_argument("times must increase strictly: time " + std::to_string(k) +
                                  " is not after time " + std::to_string(k - 1));
  RateTable t;
  t.time = std::move(time);
  t.value = std::move(value);
  t.integral.assign(t.time.size(), Vec3d());
  for (std::size_t k = 1; k < t.time.size(); ++k)
    t.integral[k] = t.integral[k - 1] + (t.value[k - 1] + t.value[k]) * (0.5 * (t.time[k] - t.time[k - 1]));
  return t;
}

Vec3d rate_at(const RateTable& t, double tau) {
  const std::size_t k = segment_of(t, tau);
  return t.value[k] + slope_of(t, k) * (tau - t.time[k]);
}

Vec3d integral_to(const RateTable& t, double tau) {
  const std::size_t k = segment_of(t, tau);
  const double h = tau - t.time[k];
  return t.integral[k] + (t.value[k] + slope_of(t, k) * (0.5 * h)) * h;
}

Vec3d oscillation_displacement(const Oscillation& o, double tau) {
  return o.amplitude * std::sin(kTwoPi * o.frequency * tau + o.phase);
}

Vec3d oscillation_velocity(const Oscillation& o, double tau) {
  const double omega = kTwoPi * o.frequency;
  return o.amplitude * (omega * std::cos(omega * tau + o.phase));
}

}  // namespace gs
