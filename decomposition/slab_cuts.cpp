#include "slab_cuts.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace gs {
namespace {

using Prefix = std::vector<std::int64_t>;  // P[c] = particles in layers [0, c)

Prefix prefix_sum(const Histogram& counts) {
  Prefix p(counts.size() + 1, 0);
  for (std::size_t i = 0; i < counts.size(); ++i) p[i + 1] = p[i] + counts[i];
  return p;
}

// Fewest runs of load <= cap that cover all layers; packing each run as full
// as possible is optimal for contiguous runs. Assumes every layer <= cap.
int runs_needed(const Histogram& counts, std::int64_t cap) {
  int runs = 1;
  std::int64_t load = 0;
  for (std::int64_t c : counts) {
    if (load + c > cap) {
      ++runs;
      load = c;
    } else {
      load += c;
    }
  }
  return runs;
}

// Smallest achievable largest-run load with n runs (binary search on the answer).
std::int64_t optimal_bottleneck(const Histogram& counts, const Prefix& p, int n) {
  const std::int64_t total = p.back();
  const std::int64_t heaviest = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
  std::int64_t lo = std::max(heaviest, (total + n - 1) / n), hi = total;
  while (lo < hi) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    if (runs_needed(counts, mid) <= n)
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

// min_start[m]: smallest c such that layers [c, L) fit in m runs of load <= cap
// (greedy packing from the top end). A cut at c >= min_start[m] leaves a
// suffix that the remaining m runs can always take.
std::vector<int> min_starts(const Prefix& p, int n, std::int64_t cap) {
  std::vector<int> start(std::size_t(n) + 1);
  int pos = int(p.size()) - 1;
  start[0] = pos;
  for (int m = 1; m <= n; ++m) {
    const int end = pos;
    while (pos > 0 && p[end] - p[pos - 1] <= cap) --pos;
    start[m] = pos;
  }
  return start;
}

// Last c with p[c] - p[from] <= cap.
int reach(const Prefix& p, int from, std::int64_t cap) {
  return int(std::upper_bound(p.begin(), p.end(), p[from] + cap) - p.begin()) - 1;
}

struct CutKey {
  std::int64_t count_miss, layer_miss;
  int c;
  bool operator<(const CutKey& o) const {
    if (count_miss != o.count_miss) return count_miss < o.count_miss;
    if (layer_miss != o.layer_miss) return layer_miss < o.layer_miss;
    return c < o.c;
  }
};

// Distances (scaled by n to stay integral) from the quantile k N / n and the even split k L / n.
CutKey key_of(const Prefix& p, int c, int k, int n) {
  const std::int64_t total = p.back(), layers = std::int64_t(p.size()) - 1;
  const std::int64_t dn = p[std::size_t(c)] * n - k * total;
  const std::int64_t dl = std::int64_t(c) * n - k * layers;
  return {dn < 0 ? -dn : dn, dl < 0 ? -dl : dl, c};
}

// Best cut in [first, last] among the layers whose prefix equals p[j]: a run
// of equal prefixes is a stretch of empty layers, where only the layer
// distance differs, so the two layers around k L / n are the candidates.
CutKey best_on_plateau(const Prefix& p, int first, int last, int j, int k, int n) {
  const auto range = std::equal_range(p.begin() + first, p.begin() + last + 1, p[std::size_t(j)]);
  const int a = int(range.first - p.begin()), b = int(range.second - p.begin()) - 1;
  const std::int64_t layers = std::int64_t(p.size()) - 1;
  const int below = int(std::clamp<std::int64_t>(k * layers / n, a, b));
  const int above = std::min(b, below + 1);
  return std::min(key_of(p, below, k, n), key_of(p, above, k, n));
}

// Best cut k in [first, last]: the prefix sum is monotone, so the quantile
// miss is smallest on the plateau at or just below the quantile.
int pick_cut(const Prefix& p, int first, int last, int k, int n) {
  const std::int64_t target = (k * p.back() + n - 1) / n;  // ceil(k N / n)
  const int j = int(std::lower_bound(p.begin() + first, p.begin() + last + 1, target) - p.begin());
  CutKey best{INT64_MAX, INT64_MAX, 0};
  if (j <= last) best = std::min(best, best_on_plateau(p, first, last, j, k, n));
  if (j - 1 >= first) best = std::min(best, best_on_plateau(p, first, last, j - 1, k, n));
  return best.c;
}

}  // namespace

std::vector<int> balanced_cuts(const Histogram& counts, int n) {
  const int layers = int(counts.size());
  if (n < 1 || layers < n)
    throw std::invalid_argument("balanced_cuts: need 1 <= n <= layers, got n = " + std::to_string(n) +
                                ", layers = " + std::to_string(layers));
  for (std::int64_t c : counts)
    if (c < 0) throw std::invalid_argument("balanced_cuts: negative count in histogram");
  const Prefix p = prefix_sum(counts);
  const std::int64_t cap = optimal_bottleneck(counts, p, n);
  const std::vector<int> min_start = min_starts(p, n, cap);
  std::vector<int> bounds(std::size_t(n) + 1, 0);
  bounds[std::size_t(n)] = layers;
  for (int k = 1; k < n; ++k) {
    const int prev = bounds[std::size_t(k - 1)];
    const int first = std::max(prev + 1, min_start[std::size_t(n - k)]);
    const int last = std::min(layers - (n - k), reach(p, prev, cap));
    // Non-empty by construction: prev leaves a suffix that n - k + 1 runs of
    // load <= cap can take, so some first run ends in [first, last].
    if (first > last) throw std::logic_error("balanced_cuts: empty cut range (bug)");
    bounds[std::size_t(k)] = pick_cut(p, first, last, k, n);
  }
  return bounds;
}

}  // namespace gs
