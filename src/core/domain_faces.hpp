#pragma once
// The six faces of the simulation domain, as bits: 2 * axis for the face at
// the domain's min, 2 * axis + 1 at its max (xmin, xmax, ymin, ymax, zmin,
// zmax). A scene leaves some open (SceneSettings::open_faces): a particle
// beyond an open face is removed, beyond a closed one it is a fault.
#include "core/hd.hpp"
#include "core/vec3.hpp"

namespace gs {

constexpr int kDomainFaces = 6;
constexpr const char* kDomainFaceNames[kDomainFaces] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};

// The faces of [lo, hi] that x is beyond.
GS_HD GS_INLINE unsigned faces_beyond(const Vec3d& x, const Vec3d& lo, const Vec3d& hi) {
  return (x.x < lo.x ? 1u : 0u) | (x.x > hi.x ? 2u : 0u) | (x.y < lo.y ? 4u : 0u) | (x.y > hi.y ? 8u : 0u) |
         (x.z < lo.z ? 16u : 0u) | (x.z > hi.z ? 32u : 0u);
}

// The two faces of each axis in `axes` (bit a: axis a, as PeriodicBox::axes).
GS_HD GS_INLINE unsigned faces_of_axes(unsigned axes) {
  return ((axes & 1u) != 0 ? 3u : 0u) | ((axes & 2u) != 0 ? 12u : 0u) | ((axes & 4u) != 0 ? 48u : 0u);
}

}  // namespace gs
