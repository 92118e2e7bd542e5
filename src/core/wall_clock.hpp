#pragma once
// Wall-clock time for the run's timings and schedules.
#include <chrono>

namespace gs {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace gs
