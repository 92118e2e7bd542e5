// `domain.periodic`: the axes that wrap, and what the scene must then
// satisfy (docs/SCENES.md, "Periodic boundaries").
#include <algorithm>
#include <cmath>

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

// Why wall w cannot meet the periodic faces of `axis`, or "" when it can: it
// must look the same at every coordinate along the axis, at every time.
std::string periodic_wall_problem(const Wall& w, int axis, const Vec3d& lo, const Vec3d& hi) {
  const std::string a = kAxisNames[axis];
  // A rotation about another axis would turn the wall out of that shape.
  if (norm2(w.angular_velocity) > 0 && !only_along(w.angular_velocity, axis))
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
      if (component(w.velocity, axis) != 0) return "a cylinder along the periodic axis " + a + " may not move along it";
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
      const std::string problem = periodic_wall_problem(s.walls[k], axis, s.domain_min, s.domain_max);
      if (!problem.empty())
        fail(item, "wall " + quoted(s.wall_names[k]) + " cannot meet the periodic boundaries of domain.periodic: " +
                       problem);
    }
}

void check_periodic_box(const Map& top, const SceneSpec& s) {
  if (s.periodic_axes == 0) return;
  const Map domain(top.get("domain"), {"min", "max", "periodic"});
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
      const bool stays = component(motion.velocity, axis) == 0 &&
                         (norm2(motion.angular_velocity) == 0 || only_along(motion.angular_velocity, axis));
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
