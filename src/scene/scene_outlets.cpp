// `outlets:` -> SceneSpec::outlets and `domain.open` -> SceneSpec::open_faces
// (docs/SCENES.md).
#include <algorithm>
#include <cmath>
#include <map>

#include "scene/scene_sections.hpp"

namespace gs::scene_yaml {

namespace {

const std::vector<std::string> kFaceNames(std::begin(kDomainFaceNames), std::end(kDomainFaceNames));

OutletRegion parse_box(const Val& v) {
  OutletRegion r;
  r.kind = OutletRegion::Kind::box;
  box_corners(Map(v, {"min", "max"}), r.min, r.max);
  return r;
}

OutletRegion parse_cylinder(const Val& v) {
  const Map c(v, {"base", "axis", "radius", "length"});
  OutletRegion r;
  r.kind = OutletRegion::Kind::cylinder;
  r.point = vec3(c.get("base"));
  r.direction = unit_vector(c.get("axis"));
  r.radius = positive(c.get("radius"));
  r.length = positive(c.get("length"));
  // Its bounding box: the end circles reach radius * sqrt(1 - axis_i^2) off the axis along axis i.
  const Vec3d top = r.point + r.direction * r.length;
  const Vec3d reach(r.radius * std::sqrt(std::max(0.0, 1 - r.direction.x * r.direction.x)),
                    r.radius * std::sqrt(std::max(0.0, 1 - r.direction.y * r.direction.y)),
                    r.radius * std::sqrt(std::max(0.0, 1 - r.direction.z * r.direction.z)));
  r.min = Vec3d(std::min(r.point.x, top.x), std::min(r.point.y, top.y), std::min(r.point.z, top.z)) - reach;
  r.max = Vec3d(std::max(r.point.x, top.x), std::max(r.point.y, top.y), std::max(r.point.z, top.z)) + reach;
  return r;
}

OutletRegion parse_half_space(const Val& v) {
  const Map h(v, {"point", "normal"});
  OutletRegion r;
  r.kind = OutletRegion::Kind::half_space;
  r.point = vec3(h.get("point"));
  r.direction = unit_vector(h.get("normal"));
  return r;
}

// Whether any point of the domain's interior lies in the region (for a
// cylinder: in its bounding box). An outlet that misses it removes nothing.
bool reaches_into(const OutletRegion& r, const Vec3d& lo, const Vec3d& hi) {
  if (r.kind == OutletRegion::Kind::half_space) {
    for (int c = 0; c < 8; ++c) {
      const Vec3d corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
      if (dot(corner - r.point, r.direction) > 0) return true;
    }
    return false;
  }
  return r.min.x < hi.x && r.min.y < hi.y && r.min.z < hi.z && r.max.x > lo.x && r.max.y > lo.y && r.max.z > lo.z;
}

void check_new_exit_name(const SceneSpec& s, const std::string& name, const Val& where) {
  for (const OutletSpec& o : s.outlets)
    if (o.name == name) fail(where, "outlet name " + quoted(name) + " is used twice");
  if (name.rfind("domain.", 0) == 0)
    fail(where, "outlet name " + quoted(name) + " is kept for the open faces of the domain; choose another");
}

}  // namespace

void parse_open_faces(const Map& domain, SceneSpec& s) {
  const Val list = domain.opt("open");
  if (!list.present()) return;
  for_each_item(list, [&](const Val& item, std::size_t) {
    const std::string face = choice(item, kFaceNames);
    const unsigned bit = 1u << unsigned(std::find(kFaceNames.begin(), kFaceNames.end(), face) - kFaceNames.begin());
    if (s.open_faces & bit) fail(item, "the face " + quoted(face) + " is listed twice");
    s.open_faces |= bit;
  });
}

void parse_outlets(const Map& top, SceneSpec& s) {
  const Val list = top.opt("outlets");
  if (!list.present()) return;
  std::map<std::string, int> unnamed;  // per kind, for default names box, box2, ...
  for_each_item(list, [&](const Val& item, std::size_t) {
    const Map m(item, {"box", "cylinder", "half_space", "name"});
    const std::string kind = m.one_of({"box", "cylinder", "half_space"});
    OutletSpec o;
    o.name = kind;
    if (m.has("name")) o.name = text(m.get("name"));
    else if (int n = ++unnamed[kind]; n > 1) o.name += std::to_string(n);
    check_new_exit_name(s, o.name, m.has("name") ? m.get("name") : item);
    const Val shape = m.get(kind);
    o.region = kind == "box" ? parse_box(shape) : kind == "cylinder" ? parse_cylinder(shape) : parse_half_space(shape);
    if (!reaches_into(o.region, s.domain_min, s.domain_max))
      fail(shape, "the outlet lies outside the domain " + str(s.domain_min) + " .. " + str(s.domain_max) +
                      (kind == "cylinder" ? " (its bounding box " + str(o.region.min) + " .. " + str(o.region.max) + ")"
                                          : std::string()) +
                      ": it would never remove a particle");
    s.outlets.push_back(o);
  });
}

}  // namespace gs::scene_yaml
