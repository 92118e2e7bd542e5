#pragma once
// What the contact pass of the measurements (docs/MEASUREMENTS.md) finds for
// one owned particle i: its particle contacts and its share of the contact
// stress, sum over partners j of 1/2 (x_i - x_j) (x) f_ij (f_ij on i, both
// particles of a contact each hold one half), and over analytic walls of
// (x_i - x_contact) (x) f (the wall takes no share). Compression is positive.
// Plain data: the engine fills it, analysis reads it.
#include <cstdint>

#include "core/hd.hpp"
#include "core/vec3.hpp"

namespace gs {

// A 3 x 3 tensor by rows: entry (a, b) is row a's component b.
struct Tensor3d {
  Vec3d x, y, z;
  GS_HD Tensor3d& operator+=(const Tensor3d& t) {
    x += t.x;
    y += t.y;
    z += t.z;
    return *this;
  }
};

// The dyad a (x) b: entry (a, b) = a_a b_b.
GS_HD GS_INLINE Tensor3d outer(const Vec3d& a, const Vec3d& b) { return {b * a.x, b * a.y, b * a.z}; }

struct ContactMeasure {
  Tensor3d stress_moment;   // [N m]: sum of branch (x) force, as above
  std::uint32_t contacts = 0;  // particle-particle contacts (overlapping partners)
};

}  // namespace gs
