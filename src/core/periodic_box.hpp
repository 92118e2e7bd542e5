#pragma once
// Periodic boundaries: the domain's axes that wrap, the nearest image of a
// separation, and a position wrapped back into [lo, hi) with its image count.
//
// Why minimum image rather than ghost copies shifted by the box length: the
// two particles of a contact each compute it from their own side, and
// d_ij = x_i - x_j, shifted by -L when above L/2 and by +L when below -L/2, is
// exactly -d_ji (IEEE subtraction and the shift are antisymmetric), so the two
// forces cancel bit for bit as in the middle of the box. A shifted copy would
// give x_i - fl(x_j + L) on one side and x_j - fl(x_i - L) on the other.
// It needs a box of at least two contact ranges on a wrapping axis, so that a
// particle touches at most one image of a partner (the loader checks it).
#include <cmath>
#include <cstdint>

#include "core/hd.hpp"
#include "core/vec3.hpp"

namespace gs {

// How many times a particle has crossed each periodic face: + for the max
// face, - for the min face. Unwrapped position = position + image * length.
struct ImageCount {
  std::int32_t x = 0, y = 0, z = 0;
};

// Component `axis` (0 x, 1 y, 2 z) of v.
GS_HD inline double component(const Vec3d& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

struct PeriodicBox {
  unsigned axes = 0;  // bit a: axis a (x = 0, y = 1, z = 2) wraps
  Vec3d lo, hi;       // the domain
  Vec3d length;       // hi - lo

  GS_HD bool wraps(int axis) const { return (axes >> axis) & 1u; }

  // The nearest image of the separation d = x_i - x_j (both inside the box).
  GS_HD GS_INLINE Vec3d nearest(Vec3d d) const {
    if (axes == 0) return d;
    if (wraps(0)) d.x = nearest_on_axis(d.x, length.x);
    if (wraps(1)) d.y = nearest_on_axis(d.y, length.y);
    if (wraps(2)) d.z = nearest_on_axis(d.z, length.z);
    return d;
  }
  GS_HD GS_INLINE Vec3d separation(const Vec3d& xi, const Vec3d& xj) const { return nearest(xi - xj); }

  // A position that has just crossed a periodic face (by less than a box
  // length, as one step's drift does) back into [lo, hi), counting the crossing.
  GS_HD GS_INLINE void wrap(Vec3d& x, ImageCount& n) const {
    if (wraps(0)) wrap_axis(x.x, n.x, lo.x, hi.x, length.x);
    if (wraps(1)) wrap_axis(x.y, n.y, lo.y, hi.y, length.y);
    if (wraps(2)) wrap_axis(x.z, n.z, lo.z, hi.z, length.z);
  }

 private:
  GS_HD static double nearest_on_axis(double d, double l) {
    if (d > 0.5 * l) return d - l;
    if (d < -0.5 * l) return d + l;
    return d;
  }
  GS_HD static void wrap_axis(double& x, std::int32_t& n, double lo, double hi, double l) {
    if (x >= hi) {
      x -= l;
      ++n;
    } else if (x < lo) {
      x += l;
      --n;
      // lo - 1e-20 + l rounds to hi: keep the particle inside [lo, hi).
      if (x >= hi) x = ::nextafter(hi, lo);  // the C function: host and device both have it
    }
  }
};

inline PeriodicBox make_periodic_box(unsigned axes, const Vec3d& lo, const Vec3d& hi) {
  return PeriodicBox{axes, lo, hi, hi - lo};
}

}  // namespace gs
