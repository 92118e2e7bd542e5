#include "io/wall_surfaces.hpp"

#include <algorithm>
#include <cmath>

#include "walls/wall_geometry.hpp"

namespace gs {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3d unit(const Vec3d& v) { return v * (1.0 / norm(v)); }

// Two unit vectors that, with unit n, make a right-handed orthonormal basis:
// u is taken across the coordinate axis least aligned with n.
void basis_across(const Vec3d& n, Vec3d& u, Vec3d& v) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const Vec3d e = ax <= ay && ax <= az ? Vec3d(1, 0, 0) : ay <= az ? Vec3d(0, 1, 0) : Vec3d(0, 0, 1);
  u = unit(cross(n, e));
  v = cross(n, u);
}

// Triangles (0, k, k + 1) over a convex polygon given in order.
void fan(WallSurface& s, std::int32_t first, std::int32_t count) {
  for (std::int32_t k = 1; k + 1 < count; ++k) s.triangles.push_back({first, first + k, first + k + 1});
}

// Where the plane (point p, unit normal n) cuts the box's 12 edges, in order
// around the polygon they bound. Corners on the plane count once.
std::vector<Vec3d> plane_cuts_box(const Vec3d& p, const Vec3d& n, const DomainBox& box) {
  Vec3d corner[8];
  for (int c = 0; c < 8; ++c)
    corner[c] = Vec3d(c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y, c & 4 ? box.max.z : box.min.z);
  std::vector<Vec3d> cuts;
  for (int a = 0; a < 8; ++a)
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (a & bit) continue;  // each edge once: from the corner without the bit
      const Vec3d &x0 = corner[a], &x1 = corner[a | bit];
      const double d0 = dot(x0 - p, n), d1 = dot(x1 - p, n);
      if (d0 == 0) cuts.push_back(x0);
      if (d1 == 0) cuts.push_back(x1);
      if ((d0 < 0 && d1 > 0) || (d0 > 0 && d1 < 0)) cuts.push_back(x0 + (d0 / (d0 - d1)) * (x1 - x0));
    }
  const double tolerance = 1e-12 * norm(box.max - box.min);
  std::vector<Vec3d> distinct;
  for (const Vec3d& x : cuts)
    if (std::none_of(distinct.begin(), distinct.end(), [&](const Vec3d& y) { return norm(x - y) <= tolerance; }))
      distinct.push_back(x);
  if (distinct.size() < 3) return {};
  Vec3d centre;
  for (const Vec3d& x : distinct) centre = centre + x;
  centre = centre * (1.0 / double(distinct.size()));
  Vec3d u, v;
  basis_across(n, u, v);
  auto angle = [&](const Vec3d& x) { return std::atan2(dot(x - centre, v), dot(x - centre, u)); };
  std::sort(distinct.begin(), distinct.end(), [&](const Vec3d& a, const Vec3d& b) { return angle(a) < angle(b); });
  return distinct;
}

WallSurface plane_surface(const Vec3d& p, const Vec3d& n, const DomainBox& box) {
  WallSurface s;
  s.vertices = plane_cuts_box(p, n, box);
  if (s.vertices.empty()) {  // the plane misses the box
    const Vec3d box_centre = 0.5 * (box.min + box.max);
    const Vec3d foot = box_centre - dot(box_centre - p, n) * n;
    const double half = 0.5 * norm(box.max - box.min);
    Vec3d u, v;
    basis_across(n, u, v);
    s.vertices = {foot - half * u - half * v, foot + half * u - half * v, foot + half * u + half * v,
                  foot - half * u + half * v};
  }
  fan(s, 0, std::int32_t(s.vertices.size()));
  return s;
}

WallSurface disk_surface(const Vec3d& centre, const Vec3d& n, double radius) {
  WallSurface s;
  Vec3d u, v;
  basis_across(n, u, v);
  s.vertices.push_back(centre);
  for (int k = 0; k < kWallSurfaceSegments; ++k) {
    const double phi = 2 * kPi * k / kWallSurfaceSegments;
    s.vertices.push_back(centre + radius * (std::cos(phi) * u + std::sin(phi) * v));
  }
  for (std::int32_t k = 0; k < kWallSurfaceSegments; ++k)
    s.triangles.push_back({0, 1 + k, 1 + (k + 1) % kWallSurfaceSegments});
  return s;
}

// Two triangles per segment between vertex rings k and n + k, closed around.
void band(WallSurface& s, std::int32_t n) {
  for (std::int32_t k = 0; k < n; ++k) {
    const std::int32_t next = (k + 1) % n;
    s.triangles.push_back({k, next, n + k});
    s.triangles.push_back({next, n + next, n + k});
  }
}

// Vertices k (base circle, radius r0) and S + k (far circle, radius r1).
WallSurface cone_surface(const Vec3d& base, const Vec3d& axis, double r0, double r1, double length) {
  WallSurface s;
  Vec3d u, v;
  basis_across(axis, u, v);
  const std::int32_t n = kWallSurfaceSegments;
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < n; ++k) {
      const double phi = 2 * kPi * k / n;
      const double along = end ? length : 0.0, radius = end ? r1 : r0;
      s.vertices.push_back(base + along * axis + radius * (std::cos(phi) * u + std::sin(phi) * v));
    }
  band(s, n);
  return s;
}

WallSurface cylinder_surface(const Vec3d& base, const Vec3d& axis, double radius, double length) {
  return cone_surface(base, axis, radius, radius, length);
}

// A plate as a ring: vertex k on the hole's rim (the centre without a hole)
// and S + k on the outer circle, in the same direction from the centre. The
// directions are 64 even ones plus, for a rectangular hole, its corners. An
// unbounded plate is drawn to half the box's diagonal.
WallSurface plate_surface(const Wall& w, const Vec3d& centre, const Vec3d& n, const DomainBox& box) {
  Vec3d u, v;
  basis_across(n, u, v);
  const bool rectangle = w.hole_half[1] > 0;
  const double a = w.hole_half[0], b = w.hole_half[1];
  if (rectangle) {
    u = unit(wall_rotate(w, w.tangent));
    v = cross(n, u);
  }
  std::vector<double> phi;
  for (int k = 0; k < kWallSurfaceSegments; ++k) phi.push_back(2 * kPi * k / kWallSurfaceSegments - kPi);
  if (rectangle)
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0}) phi.push_back(std::atan2(sy * b, sx * a));
  std::sort(phi.begin(), phi.end());
  const double outer = std::isfinite(w.radius) ? w.radius : 0.5 * norm(box.max - box.min);
  WallSurface s;
  for (int ring = 0; ring < 2; ++ring)
    for (double p : phi) {
      const double c = std::cos(p), d = std::sin(p);
      double r = outer;
      if (ring == 0) r = rectangle ? std::min(a / std::max(std::abs(c), 1e-300), b / std::max(std::abs(d), 1e-300)) : a;
      s.vertices.push_back(centre + r * (c * u + d * v));
    }
  band(s, std::int32_t(phi.size()));
  return s;
}

}  // namespace

WallSurface wall_surface(const Wall& w, const DomainBox& box) {
  const Vec3d point = wall_to_world(w, w.point), normal = unit(wall_rotate(w, w.normal));
  switch (w.kind) {
    case WallKind::plane: return plane_surface(point, normal, box);
    case WallKind::disk: return disk_surface(point, normal, w.radius);
    case WallKind::cylinder: return cylinder_surface(point, normal, w.radius, w.length);
    case WallKind::plate: return plate_surface(w, point, normal, box);
    case WallKind::cone: return cone_surface(point, normal, w.radius, w.end_radius, w.length);
  }
  return {};
}

void write_wall_surfaces(const h5::File& f, const std::string& group, const std::vector<Wall>& walls,
                         const std::vector<std::string>& names, const DomainBox& box) {
  h5::create_group(f, group);
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const WallSurface s = wall_surface(walls[k], box);
    const std::string g = group + "/" + std::to_string(k);
    h5::create_group(f, g);
    h5::write_string_attribute(f, g, "name", k < names.size() ? names[k] : "wall_" + std::to_string(k));
    h5::write_attribute(f, g, "active", std::int32_t(walls[k].active));
    h5::write_vec3(f, g + "/vertices", s.vertices);
    h5::write_array(f, g + "/triangles", s.triangles.empty() ? nullptr : s.triangles[0].data(),
                    {hsize_t(s.triangles.size()), 3});
  }
}

std::vector<WallSurfaceInfo> read_wall_surface_info(const h5::File& f, const std::string& group) {
  std::vector<WallSurfaceInfo> out;
  if (!h5::exists(f, group)) return out;
  for (std::size_t k = 0;; ++k) {
    const std::string g = group + "/" + std::to_string(k);
    if (!h5::exists(f, g)) break;
    WallSurfaceInfo info;
    info.name = h5::read_string_attribute(f, g, "name");
    info.vertices = std::size_t(h5::dims_of(f, g + "/vertices")[0]);
    info.triangles = std::size_t(h5::dims_of(f, g + "/triangles")[0]);
    out.push_back(info);
  }
  return out;
}

}  // namespace gs
