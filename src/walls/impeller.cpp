#include "walls/impeller.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gs {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TriangleMesh make_box(const Vec3d& centre, const Vec3d& u, const Vec3d& v, const Vec3d& half_extent) {
  const Vec3d w = cross(u, v);
  TriangleMeshBuilder b("box");
  // Corner (i, j, k) at centre + (+-hx) u + (+-hy) v + (+-hz) w, index i + 2 j + 4 k.
  std::int32_t corner[8];
  for (int n = 0; n < 8; ++n) {
    const double su = (n & 1) ? 1 : -1, sv = (n & 2) ? 1 : -1, sw = (n & 4) ? 1 : -1;
    corner[n] = b.vertex(centre + u * (su * half_extent.x) + v * (sv * half_extent.y) + w * (sw * half_extent.z));
  }
  // Each face counter-clockwise seen from outside.
  b.quad(corner[0], corner[2], corner[3], corner[1]);  // -w
  b.quad(corner[4], corner[5], corner[7], corner[6]);  // +w
  b.quad(corner[0], corner[1], corner[5], corner[4]);  // -v
  b.quad(corner[2], corner[6], corner[7], corner[3]);  // +v
  b.quad(corner[0], corner[4], corner[6], corner[2]);  // -u
  b.quad(corner[1], corner[3], corner[7], corner[5]);  // +u
  return b.take();
}

TriangleMesh make_revolved(const std::vector<std::pair<double, double>>& profile, int segments, double max_edge) {
  if (segments < 3) throw std::invalid_argument("a solid of revolution needs at least 3 segments");
  if (!(max_edge > 0)) throw std::invalid_argument("max_edge must be positive");
  if (profile.size() < 3 || profile.front().first != 0 || profile.back().first != 0)
    throw std::invalid_argument("a revolved profile must start and end on the axis (r = 0)");
  // Split long pieces; the interior points (r > 0) become rings.
  std::vector<std::pair<double, double>> points{profile.front()};
  for (std::size_t i = 1; i < profile.size(); ++i) {
    const auto [r0, z0] = profile[i - 1];
    const auto [r1, z1] = profile[i];
    const int pieces = std::max(1, int(std::ceil(std::hypot(r1 - r0, z1 - z0) / max_edge)));
    for (int s = 1; s <= pieces; ++s) {
      const double f = double(s) / pieces;
      points.emplace_back(s == pieces ? r1 : r0 + f * (r1 - r0), s == pieces ? z1 : z0 + f * (z1 - z0));
    }
  }
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    if (!(points[i].first > 0)) throw std::invalid_argument("a revolved profile must stay off the axis between its ends");

  TriangleMeshBuilder b("revolved");
  const int rings = int(points.size()) - 2;
  std::vector<std::int32_t> ring(std::size_t(rings) * segments);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * kPi * j / segments;
      const auto [r, z] = points[i + 1];
      ring[std::size_t(i) * segments + j] = b.vertex(Vec3d(r * std::cos(phi), r * std::sin(phi), z));
    }
  auto at = [&](int i, int j) { return ring[std::size_t(i) * segments + (j % segments)]; };
  const std::int32_t bottom = b.vertex(Vec3d(0, 0, points.front().second));
  const std::int32_t top = b.vertex(Vec3d(0, 0, points.back().second));
  for (int j = 0; j < segments; ++j) {
    b.triangle(bottom, at(0, j + 1), at(0, j));
    for (int i = 0; i + 1 < rings; ++i) b.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
    b.triangle(at(rings - 1, j), at(rings - 1, j + 1), top);
  }
  return b.take();
}

BladeLayout blade_layout(const ImpellerSpec& s) {
  const double angle = s.blade_angle_deg * kPi / 180;
  BladeLayout l;
  l.root_radius = s.blade_root_radius;
  l.half_span = 0.5 * s.blade_width * std::cos(angle) + 0.5 * s.blade_thickness * std::sin(angle);
  l.half_height = 0.5 * s.blade_width * std::sin(angle) + 0.5 * s.blade_thickness * std::cos(angle);
  const double swept = 0.5 * s.blade_diameter;
  l.tip_radius = swept > l.half_span ? std::sqrt(swept * swept - l.half_span * l.half_span) : 0;
  return l;
}

TriangleMesh make_impeller(const ImpellerSpec& s) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("impeller: " + what);
  };
  require(s.blades >= 1, "needs at least one blade");
  require(s.blade_width > 0 && s.blade_thickness > 0 && s.hub_height > 0 && s.shaft_length >= 0 &&
              s.shaft_diameter > 0 && s.hub_diameter > s.shaft_diameter,
          "dimensions must be positive, the hub wider than the shaft");
  require(s.blade_angle_deg > 0 && s.blade_angle_deg < 90, "blade angle must lie in (0, 90) degrees");
  const BladeLayout l = blade_layout(s);
  const double hub_r = 0.5 * s.hub_diameter;
  const double hub_inner = hub_r * std::cos(kPi / s.segments);  // the polygon's inner radius
  require(std::hypot(l.root_radius, l.half_span) < hub_inner,
          "blade roots must lie inside the hub (reduce blade_root_radius, blade_width or blade_thickness)");
  require(2 * l.half_height < s.hub_height, "blades must be lower than the hub");
  require(l.tip_radius > hub_r, "blade diameter must exceed the hub diameter");

  const double top = s.hub_height + s.shaft_length;
  const double shaft_r = 0.5 * s.shaft_diameter;
  std::vector<std::pair<double, double>> profile{{0, 0}, {hub_r, 0}, {hub_r, s.hub_height}};
  if (s.shaft_length > 0) {
    profile.emplace_back(shaft_r, s.hub_height);
    profile.emplace_back(shaft_r, top);
    profile.emplace_back(0, top);
  } else {
    profile.emplace_back(0, s.hub_height);
  }
  TriangleMesh mesh = make_revolved(profile, s.segments, s.max_edge);
  mesh.name = "impeller";

  const double angle = s.blade_angle_deg * kPi / 180;
  const double middle = 0.5 * (l.root_radius + l.tip_radius);
  for (int k = 0; k < s.blades; ++k) {
    const double theta = 2 * kPi * k / s.blades;
    const Vec3d radial(std::cos(theta), std::sin(theta), 0), tangential(-std::sin(theta), std::cos(theta), 0);
    const Vec3d width = tangential * std::cos(angle) + Vec3d(0, 0, std::sin(angle));
    const Vec3d centre = radial * middle + Vec3d(0, 0, 0.5 * s.hub_height);
    const Vec3d half(0.5 * (l.tip_radius - l.root_radius), 0.5 * s.blade_width, 0.5 * s.blade_thickness);
    append_mesh(mesh, make_box(centre, radial, width, half));
  }
  return mesh;
}

}  // namespace gs
