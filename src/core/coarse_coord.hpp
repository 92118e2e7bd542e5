#pragma once
// The one formula that maps a coordinate to a coarse (ownership) cell. Every
// rank, and the host and the device of each, must agree on it exactly, so it
// is written once: floor((p - lo) / edge) with no fused or reordered
// arithmetic (a subtraction and an IEEE division round the same everywhere),
// clamped to [0, dims - 1]; NaN maps to 0 so that a corrupt position cannot
// index out of range.
#include "core/hd.hpp"

namespace gs {

GS_HD inline int coarse_coord(double p, double lo, double edge, int dims) {
  const double t = (p - lo) / edge;
  if (!(t >= 0.0)) return 0;  // also catches NaN
  if (t >= double(dims)) return dims - 1;
  return int(t);
}

}  // namespace gs
