// `measurements:` -> SceneSpec::measurements (docs/SCENES.md, docs/MEASUREMENTS.md).
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "scene/scene_sections.hpp"
#include "walls/triangle_mesh.hpp"

namespace gs::scene_yaml {

namespace {

// A name becomes part of file names: letters, digits, '_' and '-' only.
std::string measurement_name(const Val& v, std::set<std::string>& taken) {
  const std::string name = text(v);
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      fail(v, quoted(name) + " may hold only letters, digits, '_' and '-' (it names output files)");
  if (!taken.insert(name).second) fail(v, "the name " + quoted(name) + " is already taken by another measurement");
  return name;
}

MeasurementTimes read_times(const Map& m, const SceneSpec& s) {
  MeasurementTimes t;
  t.every = positive(m.get("every"));
  t.start = number_or(m, "start", 0.0, nonnegative);
  if (!(t.start <= s.duration))
    fail(m.get("start"), "must not exceed the duration " + str(s.duration) + " s, got " + str(t.start));
  if (!(t.every >= s.time_step * (1 - 1e-12)))
    fail(m.get("every"), "must be at least the time step " + str(s.time_step) + " s, got " + str(t.every));
  return t;
}

bool inside_domain(const Vec3d& x, const SceneSpec& s) {
  return x.x >= s.domain_min.x && x.x <= s.domain_max.x && x.y >= s.domain_min.y && x.y <= s.domain_max.y &&
         x.z >= s.domain_min.z && x.z <= s.domain_max.z;
}

void read_rectangle(const Val& v, FlowSpec& f) {
  const Map r(v, {"axis", "half_lengths"});
  const Vec3d axis = unit_vector(r.get("axis"));
  const Vec3d in_plane = axis - f.normal * dot(axis, f.normal);
  if (!(norm(in_plane) > 1e-6)) fail(r.get("axis"), "must not be parallel to the plane's normal");
  f.axis_u = in_plane * (1.0 / norm(in_plane));
  f.axis_v = cross(f.normal, f.axis_u);
  const Val h = r.get("half_lengths");
  if (!h.node.IsSequence() || h.node.size() != 2) fail(h, "expected a list of 2 numbers [along axis, across], got " + describe(h.node));
  for_each_item(h, [&](const Val& item, std::size_t i) { (i == 0 ? f.half_length_u : f.half_length_v) = positive(item); });
  f.bound = FlowBound::rectangle;
}

void read_markers(const Map& m, FlowSpec& f) {
  if (!m.has("markers")) return;
  for_each_item(m.get("markers"), [&](const Val& item, std::size_t) {
    const int k = int(integer(item, 0, 255));
    for (int seen : f.markers)
      if (seen == k) fail(item, "marker " + std::to_string(k) + " is listed twice");
    f.markers.push_back(k);
  });
}

// A mesh surface from an STL file (relative to the scene file), as a mesh
// wall reads one; it must lie inside the domain.
void read_surface(const Val& v, const SceneSpec& s, FlowSpec& f) {
  const Map m(v, {"stl", "scale", "weld_tolerance"});
  f.surface = read_scene_stl(m, s);
  Vec3d lo, hi;
  mesh_bounds(f.surface, lo, hi);
  if (!inside_domain(lo, s) || !inside_domain(hi, s))
    fail(v, "the mesh (" + str(lo) + " to " + str(hi) + ") reaches outside the domain " + str(s.domain_min) +
                " to " + str(s.domain_max) + " (a file in mm needs scale: 0.001)");
  f.bound = FlowBound::mesh;
}

FlowSpec parse_flow(const Val& v, const SceneSpec& s, std::set<std::string>& taken) {
  const Map m(v, {"name", "plane", "mesh", "radius", "rectangle", "markers", "every", "start"});
  FlowSpec f;
  f.name = measurement_name(m.get("name"), taken);
  if (m.has("mesh")) {
    if (m.has("plane")) fail(m.get("mesh"), "give plane (a flat surface) or mesh, not both");
    for (const char* bound : {"radius", "rectangle"})
      if (m.has(bound)) fail(m.get(bound), "bounds a plane; a mesh surface is bounded by its triangles");
    read_surface(m.get("mesh"), s, f);
    read_markers(m, f);
    f.times = read_times(m, s);
    return f;
  }
  const Map plane(m.get("plane"), {"point", "normal"});
  f.point = vec3(plane.get("point"));
  if (!inside_domain(f.point, s)) fail(plane.get("point"), str(f.point) + " lies outside the domain");
  f.normal = unit_vector(plane.get("normal"));
  if (m.has("radius") && m.has("rectangle")) fail(m.get("rectangle"), "give radius (a disk) or rectangle, not both");
  if (m.has("radius")) {
    f.radius = positive(m.get("radius"));
    f.bound = FlowBound::disk;
  }
  if (m.has("rectangle")) read_rectangle(m.get("rectangle"), f);
  read_markers(m, f);
  f.times = read_times(m, s);
  return f;
}

AverageQuantity read_quantity(const Val& v) {
  std::vector<std::string> names;
  for (AverageQuantity q : all_quantities()) names.push_back(quantity_name(q));
  const std::string name = choice(v, names);
  for (AverageQuantity q : all_quantities())
    if (name == quantity_name(q)) return q;
  fail(v, "unknown quantity");
}

AverageSpec parse_average(const Val& v, const SceneSpec& s, std::set<std::string>& taken) {
  const Map m(v, {"name", "box", "bins", "quantities", "every", "start"});
  AverageSpec a;
  a.name = measurement_name(m.get("name"), taken);
  const Map box(m.get("box"), {"min", "max"});
  box_corners(box, a.min, a.max);
  if (!inside_domain(a.min, s) || !inside_domain(a.max, s))
    fail(m.get("box"), "the box " + str(a.min) + " to " + str(a.max) + " reaches outside the domain " +
                           str(s.domain_min) + " to " + str(s.domain_max));
  if (m.has("bins")) {
    const Val b = m.get("bins");
    if (!b.node.IsSequence() || b.node.size() != 3) fail(b, "expected a list of 3 bin counts [nx, ny, nz], got " + describe(b.node));
    for_each_item(b, [&](const Val& item, std::size_t i) { a.bins[i] = int(integer(item, 1, 1000000)); });
    if (double(a.bins[0]) * a.bins[1] * a.bins[2] > 1e8) fail(b, "more than 1e8 bins");
  }
  for_each_item(m.get("quantities"), [&](const Val& item, std::size_t) {
    const AverageQuantity q = read_quantity(item);
    for (AverageQuantity seen : a.quantities)
      if (seen == q) fail(item, std::string(quantity_name(q)) + " is listed twice");
    a.quantities.push_back(q);
  });
  if (a.quantities.empty()) fail(m.get("quantities"), "name at least one quantity");
  a.times = read_times(m, s);
  return a;
}

}  // namespace

void parse_measurements(const Map& top, SceneSpec& s) {
  if (!top.has("measurements")) return;
  const Map m(top.get("measurements"), {"flows", "averages"});
  std::set<std::string> taken;
  // A flow counts the segment between a particle's two sampled centres; a
  // particle that wrapped across a periodic face in between would seem to
  // have crossed everything along the box (docs/MEASUREMENTS.md).
  if (m.has("flows") && s.periodic_axes != 0)
    fail(m.get("flows"), "flows cannot be measured in a periodic scene (domain.periodic): a particle wrapping "
                         "across a periodic face between two evaluations would count as crossing the surfaces "
                         "between its two sampled centres; averages can be measured");
  if (m.has("flows"))
    for_each_item(m.get("flows"), [&](const Val& v, std::size_t) { s.measurements.flows.push_back(parse_flow(v, s, taken)); });
  if (m.has("averages"))
    for_each_item(m.get("averages"), [&](const Val& v, std::size_t) {
      s.measurements.averages.push_back(parse_average(v, s, taken));
    });
}

}  // namespace gs::scene_yaml
