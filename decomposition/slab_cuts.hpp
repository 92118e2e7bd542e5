#pragma once
#include <vector>

#include "coarse_grid.hpp"

namespace gs {

// Splits the layers [0, L) of a histogram (L = counts.size()) into n
// contiguous runs of at least one layer each and returns the n + 1 run bounds
// (bounds[0] = 0, bounds[n] = L; run r is [bounds[r], bounds[r+1])).
//
// The largest run load is minimised exactly: the step time of a rank is set
// by its particle count, so the bottleneck is what matters. Many splits reach
// that optimum; among them each cut is placed as close as possible to the
// particle-count quantile k N / n (then to the even layer split k L / n, then
// the lower layer), which spreads the slack instead of starving the last run.
// Integer arithmetic only, so the result is a pure deterministic function of
// the histogram. Requires n >= 1, L >= n and non-negative counts.
std::vector<int> balanced_cuts(const Histogram& counts, int n);

}  // namespace gs
