#include "io/h5_walls.hpp"

#include <cstdint>

#include "walls/wall_geometry.hpp"

namespace gs {
namespace {

template <class Get>
std::vector<Vec3d> column3(const std::vector<Wall>& walls, Get get) {
  std::vector<Vec3d> out;
  for (const Wall& w : walls) out.push_back(get(w));
  return out;
}

template <class Get>
std::vector<double> column(const std::vector<Wall>& walls, Get get) {
  std::vector<double> out;
  for (const Wall& w : walls) out.push_back(get(w));
  return out;
}

std::string joined_lines(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : "\n") + n;
  return s;
}

}  // namespace

void write_walls(const h5::File& f, const std::string& group, const std::vector<Wall>& walls,
                 const std::vector<std::string>& names) {
  const hsize_t n = walls.size();
  h5::create_group(f, group);
  h5::write_attribute(f, group, "count", std::int64_t(n));
  h5::write_string_attribute(f, group, "kinds", "0 plane, 1 disk, 2 cylinder, 3 plate, 4 cone");
  if (!names.empty()) {
    if (names.size() != walls.size()) throw std::invalid_argument("write_walls: one name per wall expected");
    h5::write_string_attribute(f, group, "names", joined_lines(names));
  }
  std::vector<std::int32_t> kind, material, active;
  std::vector<double> rotation, hole_half;
  for (const Wall& w : walls) {
    hole_half.insert(hole_half.end(), w.hole_half, w.hole_half + 2);
    kind.push_back(std::int32_t(w.kind));
    material.push_back(w.material);
    active.push_back(std::int32_t(w.active));
    rotation.insert(rotation.end(), w.rotation, w.rotation + 9);
  }
  const std::string g = group + "/";
  h5::write_vector(f, g + "kind", kind);
  h5::write_vector(f, g + "material", material);
  h5::write_vector(f, g + "active", active);
  h5::write_vec3(f, g + "point", column3(walls, [](const Wall& w) { return w.point; }));
  h5::write_vec3(f, g + "normal", column3(walls, [](const Wall& w) { return w.normal; }));
  h5::write_vector(f, g + "radius", column(walls, [](const Wall& w) { return w.radius; }));
  h5::write_vector(f, g + "length", column(walls, [](const Wall& w) { return w.length; }));
  h5::write_array(f, g + "hole_half", hole_half.data(), {n, 2});
  h5::write_vec3(f, g + "tangent", column3(walls, [](const Wall& w) { return w.tangent; }));
  h5::write_vector(f, g + "end_radius", column(walls, [](const Wall& w) { return w.end_radius; }));
  h5::write_vec3(f, g + "velocity", column3(walls, [](const Wall& w) { return w.velocity; }));
  h5::write_vec3(f, g + "angular_velocity", column3(walls, [](const Wall& w) { return w.angular_velocity; }));
  h5::write_vec3(f, g + "axis_point", column3(walls, [](const Wall& w) { return w.axis_point; }));
  h5::write_array(f, g + "rotation", rotation.data(), {n, 3, 3});
  h5::write_vec3(f, g + "shift", column3(walls, [](const Wall& w) { return w.shift; }));
  h5::write_vec3(f, g + "current_point", column3(walls, [](const Wall& w) { return wall_to_world(w, w.point); }));
  h5::write_vec3(f, g + "current_normal", column3(walls, [](const Wall& w) { return wall_rotate(w, w.normal); }));
}

std::vector<Wall> read_walls(const h5::File& f, const std::string& group) {
  const std::string g = group + "/";
  const std::vector<hsize_t> dims = h5::dims_of(f, g + "kind");
  if (dims.size() != 1) throw h5::FormatError("dataset " + f.path() + ":/" + g + "kind is not one-dimensional");
  const hsize_t n = dims[0];
  const auto kind = h5::read_array<std::int32_t>(f, g + "kind", {n});
  const auto material = h5::read_array<std::int32_t>(f, g + "material", {n});
  const auto point = h5::read_vec3(f, g + "point", n), normal = h5::read_vec3(f, g + "normal", n);
  const auto radius = h5::read_array<double>(f, g + "radius", {n}), length = h5::read_array<double>(f, g + "length", {n});
  const auto velocity = h5::read_vec3(f, g + "velocity", n);
  const auto angular_velocity = h5::read_vec3(f, g + "angular_velocity", n);
  const auto axis_point = h5::read_vec3(f, g + "axis_point", n), shift = h5::read_vec3(f, g + "shift", n);
  const auto rotation = h5::read_array<double>(f, g + "rotation", {n, 3, 3});
  // Thin walls' parameters, in files written since plates and cones exist.
  const bool sheets = h5::exists(f, g + "end_radius");
  const auto hole_half = sheets ? h5::read_array<double>(f, g + "hole_half", {n, 2}) : std::vector<double>(2 * n);
  const auto tangent = sheets ? h5::read_vec3(f, g + "tangent", n) : std::vector<Vec3d>(n);
  const auto end_radius = sheets ? h5::read_array<double>(f, g + "end_radius", {n}) : std::vector<double>(n);
  std::vector<Wall> walls(n);
  for (hsize_t i = 0; i < n; ++i) {
    if (kind[i] < int(WallKind::plane) || kind[i] > int(WallKind::cone))
      throw h5::FormatError("wall " + std::to_string(i) + " in " + f.path() + " has unknown kind " +
                            std::to_string(kind[i]));
    Wall& w = walls[i];
    w.kind = WallKind(kind[i]);
    w.material = material[i];
    w.point = point[i];
    w.normal = normal[i];
    w.radius = radius[i];
    w.length = length[i];
    w.velocity = velocity[i];
    w.angular_velocity = angular_velocity[i];
    w.axis_point = axis_point[i];
    for (int k = 0; k < 9; ++k) w.rotation[k] = rotation[9 * i + k];
    w.shift = shift[i];
    w.hole_half[0] = hole_half[2 * i];
    w.hole_half[1] = hole_half[2 * i + 1];
    w.tangent = tangent[i];
    w.end_radius = end_radius[i];
  }
  return walls;
}

std::array<double, kWallStateSize> wall_state(const Wall& w) {
  std::array<double, kWallStateSize> s{};
  int k = 0;
  auto put = [&](const Vec3d& v) { s[k++] = v.x; s[k++] = v.y; s[k++] = v.z; };
  s[k++] = double(int(w.kind));
  s[k++] = double(w.material);
  put(w.point);
  put(w.normal);
  s[k++] = w.radius;
  s[k++] = w.length;
  put(w.velocity);
  put(w.angular_velocity);
  put(w.axis_point);
  for (double r : w.rotation) s[k++] = r;
  put(w.shift);
  return s;
}

}  // namespace gs
