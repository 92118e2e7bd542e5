#pragma once
// When periodic events of a run (the mixing analysis) fall, in steps.
#include <algorithm>
#include <cmath>

namespace gs {

// Steps of an event due at the times start, start + every, ...: the k-th at
// the step nearest its own time, as a run of that duration ends there, not
// k rounded intervals after the first (which drift off by a step or more
// over many: a mixer's 32nd revolution was missed that way).
struct Schedule {
  double start = 0, every = 0, dt = 1;
  long long step_of(long long k) const { return std::llround((start + double(k) * every) / dt); }
  bool due(long long step) const {
    if (!(every > 0)) return false;
    const long long k = std::llround((double(step) * dt - start) / every);
    return k >= 0 && step_of(k) == step;
  }
  // The first due step after `step`.
  long long next_after(long long step) const {
    long long k = std::max(0LL, static_cast<long long>(std::floor((double(step) * dt - start) / every)) - 1);
    while (step_of(k) <= step) ++k;
    return step_of(k);
  }
};

}  // namespace gs
