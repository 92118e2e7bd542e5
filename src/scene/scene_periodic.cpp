// `domain.periodic`: the axes that wrap, and what the scene must then
// satisfy (docs/SCENES.md, "Periodic boundaries").
#include <algorithm>
#include <cmath>

#include "core/domain_faces.hpp"
#include "scene/fill_region.hpp"
#include "scene/particle_sources.hpp"
#include "scene/scene_sections.hpp"

namespace gs::scene_yaml {
namespace {

const char* const kAxisNames[3] = {"x", "y", "z"};

// Whether v points along `axis` alone (its other components vanish).
bool only_along(const Vec3d& v, int axis) {
  for (int b = 0; b < 3; ++b)
    if (b != axis && std::abs(component(v, b)) > 1e-12 * norm(v)) return false;
  return true;
}

// Whether the motion of a wall or mesh (its constant motion and its timeline)
// ever translates it along `axis`, or turns it about another axis.
bool moves_along(const Vec3d& velocity, const Timeline& t, int axis) {
  if (component(velocity, axis) != 0) return true;
  for (const Vec3d& v : t.velocity.value)
    if (component(v, axis) != 0) return true;
  return !t.oscillation.none() && component(t.oscillation.amplitude, axis) != 0;
}
bool turns_across(const Vec3d& angular_velocity, const Timeline& t, int axis) {
  if (norm2(angular_velocity) > 0 && !only_along(angular_velocity, axis)) return true;
  for (const Vec3d& w : t.angular_velocity.value)
    if (norm2(w) > 0 && !only_along(w, axis)) return true;
  return false;
}

// The extent along `axis` of a circle of radius r centred at c across unit normal n.
void add_rim_extent(const Vec3d& c, const Vec3d& n, double r, int axis, double& lo, double& hi) {
  const double na = component(n, axis);
  const double half = r * std::sqrt(std::max(0.0, 1 - na * na));
  lo = std::min(lo, component(c, axis) - half);
  hi = std::max(hi, component(c, axis) + half);
}

// The extent along `axis` of a plate or cone wall (reference pose).
void sheet_extent(const Wall& w, int axis, double& e0, double& e1) {
  e0 = HUGE_VAL;
  e1 = -HUGE_VAL;
  add_rim_extent(w.point, w.normal, w.radius, axis, e0, e1);
  if (w.kind == WallKind::cone) add_rim_extent(w.point + w.normal * w.length, w.normal, w.end_radius, axis, e0, e1);
}

// Why wall w (with its timeline t) cannot meet the periodic faces of `axis`,
// or "" when it can: it must look the same at every coordinate along the
// axis, at every time, or (a plate or cone) stay clear of the faces.
std::string periodic_wall_problem(const Wall& w, const Timeline& t, int axis, const Vec3d& lo, const Vec3d& hi) {
  const std::string a = kAxisNames[axis];
  // A rotation about another axis would turn the wall out of that shape.
  if (turns_across(w.angular_velocity, t, axis))
    return "it rotates about an axis that is not along the periodic axis " + a;
  switch (w.kind) {
    case WallKind::plane:
      if (std::abs(component(w.normal, axis)) > 1e-12)
        return "a plane crossing the periodic axis " + a + " (its normal has a " + a +
               " component) would stop at the periodic faces; only planes parallel to a periodic axis can meet them";
      return "";
    case WallKind::disk:
      return "a disk (a cylinder's end cap) ends inside the periodic box along " + a +
             "; use caps: none on a cylinder along a periodic axis";
    case WallKind::cylinder: {
      if (!only_along(w.normal, axis))
        return "a cylinder whose axis is not along the periodic axis " + a + " would stop at the periodic faces";
      const double p0 = component(w.point, axis), p1 = p0 + w.length * component(w.normal, axis);
      if (std::min(p0, p1) > component(lo, axis) || std::max(p0, p1) < component(hi, axis))
        return "a cylinder along the periodic axis " + a + " must span the domain along it (from " +
               str(component(lo, axis)) + " to " + str(component(hi, axis)) + " m), this one spans " +
               str(std::min(p0, p1)) + " to " + str(std::max(p0, p1)) + " m";
      if (moves_along(w.velocity, t, axis)) return "a cylinder along the periodic axis " + a + " may not move along it";
      return "";
    }
    case WallKind::plate:
    case WallKind::cone: {
      // A sheet is touched at the particle's own position, not at an image:
      // it must end inside the box along the axis and stay there (the
      // clearance of a particle diameter: check_periodic_box).
      const std::string what = w.kind == WallKind::plate ? "a plate" : "a cone";
      double e0, e1;
      sheet_extent(w, axis, e0, e1);
      if (!(e0 > component(lo, axis) && e1 < component(hi, axis)))
        return what + " reaching the periodic faces along " + a +
               " would stop at them (sheets are not wrapped); it must end inside the domain along " + a +
               " (a plane parallel to " + a + " can meet them)";
      if (moves_along(w.velocity, t, axis)) return what + " may not move along the periodic axis " + a;
      return "";
    }
  }
  return "";
}


}  // namespace

unsigned parse_periodic_axes(const Val& v) {
  unsigned axes = 0;
  if (!v.node.IsSequence()) fail(v, "expected a list of axes such as [x, y], got " + describe(v.node));
  for_each_item(v, [&](const Val& item, std::size_t) {
    const std::string a = choice(item, {"x", "y", "z"});
    const unsigned bit = 1u << (a[0] - 'x');
    if (axes & bit) fail(item, "axis " + a + " is listed twice");
    axes |= bit;
  });
  return axes;
}

void check_periodic_walls(const SceneSpec& s, std::size_t first_wall, const Val& item) {
  for (std::size_t k = first_wall; k < s.walls.size(); ++k)
    for (int axis = 0; axis < 3; ++axis) {
      if (!((s.periodic_axes >> axis) & 1u)) continue;
      const std::string problem =
          periodic_wall_problem(s.walls[k], timeline_of(s.wall_timelines, k), axis, s.domain_min, s.domain_max);
      if (!problem.empty())
        fail(item, "wall " + quoted(s.wall_names[k]) + " cannot meet the periodic boundaries of domain.periodic: " +
                       problem);
    }
}

void check_open_periodic_faces(const Map& domain, const SceneSpec& s) {
  const unsigned both = s.open_faces & faces_of_axes(s.periodic_axes);
  if (both == 0) return;
  for_each_item(domain.get("open"), [&](const Val& item, std::size_t) {
    const std::string face = text(item);
    for (int f = 0; f < kDomainFaces; ++f)
      if ((both & (1u << f)) != 0 && face == kDomainFaceNames[f])
        fail(item, "the face " + quoted(face) + " cannot be open: the axis " + kAxisNames[f / 2] +
                       " is periodic (domain.periodic), so a particle leaving through that face comes back at the "
                       "other; remove it from domain.open or " + kAxisNames[f / 2] + " from domain.periodic");
  });
}

void check_periodic_box(const Map& top, const SceneSpec& s) {
  if (s.periodic_axes == 0) return;
  const Map domain(top.get("domain"), {"min", "max", "open", "periodic"});
  const Val where = domain.get("periodic");
  const double diameter = 2 * largest_radius(s);
  const Vec3d length = s.domain_max - s.domain_min;
  for (int axis = 0; axis < 3; ++axis) {
    if (!((s.periodic_axes >> axis) & 1u)) continue;
    const std::string a = kAxisNames[axis];
    // A particle must touch at most one image of a partner: its force sum
    // goes by partner id, and both images would carry the same id.
    if (!(component(length, axis) >= 2 * diameter))
      fail(where, "the domain is " + str(component(length, axis)) + " m long along the periodic axis " + a +
                      ", shorter than two largest particle diameters (2 x " + str(diameter) +
                      " m): a particle could touch two images of the same partner; lengthen the domain along " + a);
  }
  // Inlets may reach the periodic faces: insertion checks a candidate
  // against the particles' periodic images (engine/insertion.hpp).
  // Plates and cones (one wall per `plate` or `cone` entry, in order) are
  // touched at the particle's own position too: a largest diameter clear.
  if (top.has("walls")) {
    std::size_t k = 0;
    for_each_item(top.get("walls"), [&](const Val& item, std::size_t) {
      const YAML::Node& entry = item.node;
      if (!entry.IsMap() || !(entry["plate"] || entry["cone"])) return;
      while (k < s.walls.size() && s.walls[k].kind != WallKind::plate && s.walls[k].kind != WallKind::cone) ++k;
      if (k == s.walls.size()) return;
      const Wall& w = s.walls[k++];
      for (int axis = 0; axis < 3; ++axis) {
        if (!((s.periodic_axes >> axis) & 1u)) continue;
        double e0, e1;
        sheet_extent(w, axis, e0, e1);
        if (!(e0 >= component(s.domain_min, axis) + diameter && e1 <= component(s.domain_max, axis) - diameter))
          fail(item, std::string(w.kind == WallKind::plate ? "a plate" : "a cone") + " must keep a largest particle diameter (" +
                         str(diameter) + " m) clear of the periodic faces along " + kAxisNames[axis] + " (it spans " +
                         str(e0) + " to " + str(e1) + " m); sheets are not wrapped");
      }
    });
  }
  // Mesh m came from the m-th `mesh` entry of the walls list. A mesh is
  // contacted at the particle's own position only, so it must keep clear of
  // the periodic faces, and its motion must keep it so.
  if (s.meshes.n_meshes() == 0) return;
  std::int32_t m = 0;
  for_each_item(top.get("walls"), [&](const Val& item, std::size_t) {
    const YAML::Node& entry = item.node;  // const: looking a key up must not add it
    if (!entry.IsMap() || !entry["mesh"]) return;
    Vec3d lo, hi;
    mesh_reference_bounds(s.meshes, m, lo, hi);
    const MeshMotion& motion = s.meshes.motion[std::size_t(m)];
    for (int axis = 0; axis < 3; ++axis) {
      if (!((s.periodic_axes >> axis) & 1u)) continue;
      const std::string a = kAxisNames[axis];
      const bool clear = component(lo, axis) >= component(s.domain_min, axis) + diameter &&
                         component(hi, axis) <= component(s.domain_max, axis) - diameter;
      const bool stays = !moves_along(motion.velocity, motion.timeline, axis) &&
                         !turns_across(motion.angular_velocity, motion.timeline, axis);
      if (!clear || !stays)
        fail(item, "mesh " + quoted(s.meshes.names[std::size_t(m)]) +
                       " must keep a largest particle diameter (" + str(diameter) +
                       " m) clear of the periodic faces along " + a +
                       " (it spans " + str(component(lo, axis)) + " to " + str(component(hi, axis)) +
                       " m) and move only across that axis or turn about it; meshes are not wrapped");
    }
    ++m;
  });
}

}  // namespace gs::scene_yaml
