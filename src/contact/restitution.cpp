#include "contact/restitution.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gs {

double clamped_restitution(double zeta) {
  if (zeta == 1) return std::exp(-2.0);
  if (zeta < 1) return std::exp(-2 * zeta * std::acos(zeta) / std::sqrt(1 - zeta * zeta));
  return std::exp(-2 * zeta * std::acosh(zeta) / std::sqrt(zeta * zeta - 1));
}

// Both models share the restitution law (see the header), so `model` only
// names which contact is meant.
double damping_ratio(ContactModel /*model*/, double e) {
  if (!(e > 0 && e <= 1)) throw std::invalid_argument("restitution must lie in (0, 1], got " + std::to_string(e));
  if (e == 1) return 0;
  // e falls monotonically from 1 at zeta = 0 towards 0 as zeta grows.
  double lo = 0, hi = 1;
  while (clamped_restitution(hi) > e) hi *= 2;
  while (hi - lo > 1e-15 * hi) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (clamped_restitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace gs
