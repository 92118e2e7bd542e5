// The thin walls of a scene's `walls:` list (docs/SCENES.md): `plate` (a
// plane with a circular or rectangular hole, an annular disk) and `cone` (a
// hopper), with the checks that name their keys.
#include <cmath>
#include <limits>

#include "scene/scene_sheets.hpp"

namespace gs::scene_yaml {
namespace {

void parse_hole(const Val& v, Wall& w) {
  const Map m(v, {"radius", "lengths", "along"});
  const std::string shape = m.one_of({"radius", "lengths"});
  if (shape == "radius") {
    w.hole_half[0] = positive(m.get("radius"));
    if (m.has("along")) fail(m.get("along"), "only a rectangular hole (`lengths`) has a direction");
    if (!(w.hole_half[0] < w.radius))
      fail(m.get("radius"), "the hole (radius " + str(w.hole_half[0]) + " m) does not fit in the plate (radius " +
                                str(w.radius) + " m)");
    return;
  }
  const Val lengths = m.get("lengths");
  std::vector<double> l;
  for_each_item(lengths, [&](const Val& x, std::size_t) { l.push_back(positive(x)); });
  if (l.size() != 2) fail(lengths, "expected two lengths [along, across], got " + std::to_string(l.size()));
  w.hole_half[0] = 0.5 * l[0];
  w.hole_half[1] = 0.5 * l[1];
  const Vec3d along = unit_vector(m.get("along"));
  const Vec3d in_plane = along - dot(along, w.normal) * w.normal;
  if (!(norm(in_plane) > 1e-6)) fail(m.get("along"), "must not be along the plate's normal");
  w.tangent = in_plane * (1.0 / norm(in_plane));
  if (!(std::hypot(w.hole_half[0], w.hole_half[1]) < w.radius))
    fail(lengths, "the hole (" + str(l[0]) + " x " + str(l[1]) + " m) does not fit in the plate (radius " +
                      str(w.radius) + " m)");
}

}  // namespace

Wall parse_plate(const Val& v, const Wall& proto) {
  const Map m(v, {"point", "normal", "radius", "hole"});
  Wall w = proto;
  w.kind = WallKind::plate;
  w.point = vec3(m.get("point"));
  w.normal = unit_vector(m.get("normal"));
  w.radius = m.has("radius") ? positive(m.get("radius")) : std::numeric_limits<double>::infinity();
  if (m.has("hole")) parse_hole(m.get("hole"), w);
  return w;
}

Wall parse_cone(const Val& v, const Wall& proto) {
  const Map m(v, {"base", "axis", "length", "base_radius", "half_angle"});
  Wall w = proto;
  w.kind = WallKind::cone;
  w.point = vec3(m.get("base"));
  w.normal = unit_vector(m.get("axis"));
  w.length = positive(m.get("length"));
  w.radius = nonnegative(m.get("base_radius"));
  const double degrees = number(m.get("half_angle"));
  if (!(degrees > 0 && degrees < 90))
    fail(m.get("half_angle"), "must lie in (0, 90) degrees (between the axis and the wall), got " + str(degrees));
  w.end_radius = w.radius + w.length * std::tan(degrees * M_PI / 180);
  return w;
}

}  // namespace gs::scene_yaml
