#pragma once
// Where particles leave a run (docs/SCENES.md, `outlets` and `domain.open`):
// outlet regions, and the faces of the domain left open. A particle whose
// centre is inside an outlet, or beyond an open face, is removed at the step
// it is found there; one beyond a closed face is a fault, as it always was.
// The test is a plain host/device function, so both backends run the same one.
#include <cstdint>
#include <string>
#include <vector>

#include "core/domain_faces.hpp"

namespace gs {

struct OutletRegion {
  enum class Kind : std::int32_t { box, cylinder, half_space };
  Kind kind = Kind::box;
  Vec3d min, max;      // box: its corners
  Vec3d point;         // cylinder: the centre of its base circle; half-space: a point on its plane
  Vec3d direction;     // cylinder: unit axis; half-space: unit normal, pointing into the removed side
  double radius = 0;   // cylinder
  double length = 0;   // cylinder, along `direction` from `point`
};

// Whether the centre x lies in the region (its boundary included).
GS_HD GS_INLINE bool outlet_contains(const OutletRegion& r, const Vec3d& x) {
  switch (r.kind) {
    case OutletRegion::Kind::box:
      return x.x >= r.min.x && x.y >= r.min.y && x.z >= r.min.z && x.x <= r.max.x && x.y <= r.max.y &&
             x.z <= r.max.z;
    case OutletRegion::Kind::cylinder: {
      const Vec3d d = x - r.point;
      const double along = dot(d, r.direction);
      if (!(along >= 0 && along <= r.length)) return false;
      const Vec3d across = d - r.direction * along;
      return norm2(across) <= r.radius * r.radius;
    }
    case OutletRegion::Kind::half_space:
      return dot(x - r.point, r.direction) >= 0;
  }
  return false;
}

struct OutletSpec {
  std::string name;
  OutletRegion region;
};

// The exits of a scene, in the order a particle is attributed to them (the
// first that holds it): its outlets in scene order, then its open faces
// from xmin to zmax. The removal log names them so (outlet names, then
// `domain.<face>`).
struct Exits {
  std::vector<OutletRegion> outlets;
  unsigned open_faces = 0;
  std::vector<std::string> names;  // one per outlet, then one per open face
  bool any() const { return !outlets.empty() || open_faces != 0; }
};

inline Exits exits_of(const std::vector<OutletSpec>& outlets, unsigned open_faces) {
  Exits e;
  e.open_faces = open_faces;
  for (const OutletSpec& o : outlets) {
    e.outlets.push_back(o.region);
    e.names.push_back(o.name);
  }
  for (int f = 0; f < kDomainFaces; ++f)
    if (open_faces & (1u << f)) e.names.push_back(std::string("domain.") + kDomainFaceNames[f]);
  return e;
}

}  // namespace gs
