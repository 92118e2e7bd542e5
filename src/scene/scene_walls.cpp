// The `walls:` section of a scene and the t = 0 wall geometry checks.
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "scene/scene_loader.hpp"
#include "scene/scene_motion.hpp"
#include "scene/scene_sections.hpp"
#include "scene/scene_sheets.hpp"
#include "walls/sheet_geometry.hpp"
#include "walls/stl.hpp"

namespace gs {

double wall_penetration(const Wall& w, const Vec3d& c, double r) {
  const Vec3d d = c - w.point;
  const double h = dot(d, w.normal);  // height above the plane / position along the axis
  switch (w.kind) {
    case WallKind::plane:
      return r - h;  // the whole back side counts as inside the wall
    case WallKind::disk: {
      const double rho = norm(d - h * w.normal);
      if (rho <= w.radius) return r - std::abs(h);
      return r - std::hypot(rho - w.radius, h);  // the nearest wall point is on the rim
    }
    case WallKind::cylinder:
      if (h < 0 || h > w.length) return -r;
      return norm(d - h * w.normal) + r - w.radius;
    case WallKind::plate:
    case WallKind::cone:  // thin sheets: the distance to the nearest point, from either side
      return r - norm(d - sheet_nearest(w, c));
  }
  return -r;
}

namespace scene_yaml {

namespace {

const std::vector<std::string> kWallKeys = {"plane", "box",  "cylinder", "plate",  "cone",
                                            "mesh",  "name", "material", "motion", "active"};

void check_new_name(const SceneSpec& s, const std::string& name, const Val& where) {
  for (const auto& other : s.wall_names)
    if (other == name) fail(where, "wall name " + quoted(name) + " is used twice");
  for (const auto& other : s.meshes.names)
    if (other == name) fail(where, "wall name " + quoted(name) + " is used twice");
}

void add_wall(SceneSpec& s, const Wall& w, const std::string& name, const Val& where) {
  check_new_name(s, name, where);
  s.walls.push_back(w);
  s.wall_names.push_back(name);
}

void add_plane(SceneSpec& s, const Wall& proto, const Val& v, const std::string& name) {
  const Map m(v, {"point", "normal"});
  Wall w = proto;
  w.kind = WallKind::plane;
  w.point = vec3(m.get("point"));
  w.normal = unit_vector(m.get("normal"));
  add_wall(s, w, name, v);
}

// Six planes facing into the box.
void add_box(SceneSpec& s, const Wall& proto, const Val& v, const std::string& name) {
  Vec3d lo, hi;
  box_corners(Map(v, {"min", "max"}), lo, hi);
  const char* axis_name[3] = {"x", "y", "z"};
  const Vec3d unit[3] = {Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(0, 0, 1)};
  for (int a = 0; a < 3; ++a) {
    Wall w = proto;
    w.kind = WallKind::plane;
    w.point = lo;
    w.normal = unit[a];
    add_wall(s, w, name + "." + axis_name[a] + "min", v);
    w.point = hi;
    w.normal = Vec3d() - unit[a];  // not -unit[a], which would print -0
    add_wall(s, w, name + "." + axis_name[a] + "max", v);
  }
}

// The inside surface, plus end caps facing into the cylinder.
void add_cylinder(SceneSpec& s, const Wall& proto, const Val& v, const std::string& name) {
  const Map m(v, {"base", "axis", "radius", "length", "caps"});
  Wall side = proto;
  side.kind = WallKind::cylinder;
  side.point = vec3(m.get("base"));
  side.normal = unit_vector(m.get("axis"));
  side.radius = positive(m.get("radius"));
  side.length = positive(m.get("length"));
  const std::string caps = m.has("caps") ? choice(m.get("caps"), {"none", "bottom", "top", "both"}) : "none";
  add_wall(s, side, name, v);

  Wall cap = proto;
  cap.kind = WallKind::disk;
  cap.radius = side.radius;
  if (caps == "bottom" || caps == "both") {
    cap.point = side.point;
    cap.normal = side.normal;
    add_wall(s, cap, name + ".bottom", v);
  }
  if (caps == "top" || caps == "both") {
    cap.point = side.point + side.length * side.normal;
    cap.normal = -side.normal;
    add_wall(s, cap, name + ".top", v);
  }
}

// A triangle mesh from an STL file (relative to the scene file), with the
// entry's material and motion (docs/MESHES.md).
void add_mesh_wall(SceneSpec& s, const Wall& proto, const Timeline& timeline, const Val& v, const std::string& name) {
  const Map m(v, {"stl", "scale", "weld_tolerance", "crease_angle"});
  check_new_name(s, name, v);
  const double crease = number_or(m, "crease_angle", kDefaultCreaseAngleDeg, nonnegative);
  if (!(crease < 90)) fail(m.get("crease_angle"), "must be below 90 degrees");
  TriangleMesh mesh = read_scene_stl(m, s);
  mesh.name = name;
  const MeshMotion motion{proto.velocity, proto.angular_velocity, proto.axis_point, proto.motion_start, timeline};
  try {
    add_mesh(s.meshes, mesh, proto.material, motion, crease);
  } catch (const std::exception& e) {
    fail(v, cut(e.what(), 4 * kEchoLength));
  }
  if (s.meshes.n_triangles() >= kMaxMeshFeatures || s.meshes.n_vertices() >= kMaxMeshFeatures ||
      s.meshes.n_edges >= kMaxMeshFeatures)
    fail(v, "the scene's meshes exceed 2^28 triangles, edges or vertices");
}

}  // namespace

TriangleMesh read_scene_stl(const Map& m, const SceneSpec& s) {
  const Val file = m.get("stl");
  std::filesystem::path path(text(file));
  if (path.is_relative()) path = std::filesystem::path(s.path).parent_path() / path;
  StlReadOptions options;
  options.scale = number_or(m, "scale", 1.0, positive);
  options.weld_tolerance = number_or(m, "weld_tolerance", 0.0, nonnegative);
  try {
    return read_stl(path.string(), options);
  } catch (const std::exception& e) {
    fail(file, cut(e.what(), 4 * kEchoLength));
  }
}

int material_index(const SceneSpec& s, const Val& v) {
  const std::string name = text(v);
  std::vector<std::string> known;
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    if (s.materials[m].name == name) return int(m);
    known.push_back(s.materials[m].name);
  }
  fail(v, "unknown material " + quoted(name) + "; defined materials: " + join(known));
}

void check_mesh_binning(const Map& top, const SceneSpec& s, double cell_size, double skin) {
  if (s.meshes.n_meshes() == 0) return;
  const MeshBinningSize size = binning_size(s.meshes, cell_size, run_binning(cell_size, skin));
  const Vec3d domain = s.domain_max - s.domain_min;
  // Mesh m came from the m-th `mesh` entry of the walls list.
  std::int32_t m = 0;
  for_each_item(top.get("walls"), [&](const Val& item, std::size_t) {
    const Map wall(item, kWallKeys);
    if (!wall.has("mesh")) return;
    Vec3d lo, hi;
    mesh_reference_bounds(s.meshes, m, lo, hi);
    if (!(size.cells[m] <= kMaxGridCells && size.entries[m] <= kMaxBinEntries))
      fail(wall.get("mesh"), "mesh " + quoted(s.meshes.names[m]) + " spans " + str(hi - lo) +
                                 " m against a domain of " + str(domain) + " m: binning it in cells of " +
                                 str(cell_size) + " m (the largest particle diameter and the Verlet skin) needs " +
                                 str(size.cells[m]) +
                                 " cells (at most " + str(kMaxGridCells) + ") and up to " + str(size.entries[m]) +
                                 " triangle entries (at most 2^31 - 1), about " +
                                 str(4 * (size.cells[m] + size.entries[m]) / 1073741824.0) +
                                 " GiB; is the STL in millimetres? `scale: 0.001` reads it in metres");
    ++m;
  });
  if (!(size.total_cells() <= kMaxGridCells && size.total_entries() <= kMaxBinEntries))
    fail(top.get("walls"), "the meshes together need " + str(size.total_cells()) + " cells (at most " +
                               str(kMaxGridCells) + ") and up to " + str(size.total_entries()) +
                               " triangle entries (at most 2^31 - 1) in cells of " +
                               str(cell_size) +
                               " m (the largest particle diameter and the Verlet skin); use coarser meshes");
}

void parse_walls(const Map& top, SceneSpec& s) {
  const Val list = top.opt("walls");
  if (!list.present()) return;
  std::map<std::string, int> unnamed;  // per kind, for default names box, box2, ...
  for_each_item(list, [&](const Val& item, std::size_t) {
    const Map m(item, kWallKeys);
    const std::string kind = m.one_of({"plane", "box", "cylinder", "plate", "cone", "mesh"});
    Wall proto;
    Timeline timeline;  // shared, as the motion, by every wall of the entry
    proto.material = material_index(s, m.get("material"));
    if (m.has("motion")) parse_motion(m.get("motion"), proto, timeline);
    if (m.has("active")) timeline.active = parse_active(m.get("active"));
    std::string name = kind;
    if (m.has("name")) {
      name = text(m.get("name"));
    } else if (int n = ++unnamed[kind]; n > 1) {
      name += std::to_string(n);
    }
    const Val shape = m.get(kind);
    const std::size_t first_wall = s.walls.size();
    if (kind == "plane") add_plane(s, proto, shape, name);
    if (kind == "box") add_box(s, proto, shape, name);
    if (kind == "cylinder") add_cylinder(s, proto, shape, name);
    if (kind == "plate") add_wall(s, parse_plate(shape, proto), name, shape);
    if (kind == "cone") add_wall(s, parse_cone(shape, proto), name, shape);
    if (kind == "mesh") add_mesh_wall(s, proto, timeline, shape, name);
    s.wall_timelines.resize(s.walls.size(), timeline);
    check_periodic_walls(s, first_wall, item);
  });
  if (s.walls.size() > std::size_t(kMaxWalls))
    fail(list, "the entries expand to " + std::to_string(s.walls.size()) + " walls; at most " +
                   std::to_string(kMaxWalls) + " are allowed (a box counts 6, a cylinder up to 3)");
}

}  // namespace scene_yaml
}  // namespace gs
