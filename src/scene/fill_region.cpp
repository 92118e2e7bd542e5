#include "scene/fill_region.hpp"

#include <algorithm>
#include <cmath>

namespace gs {

double region_volume(const FillRegion& reg) {
  if (reg.kind == FillRegion::Kind::cylinder) return M_PI * reg.radius * reg.radius * reg.length;
  const Vec3d d = reg.max - reg.min;
  return d.x * d.y * d.z;
}

void region_bounds(const FillRegion& reg, Vec3d& lo, Vec3d& hi) {
  if (reg.kind == FillRegion::Kind::box) {
    lo = reg.min;
    hi = reg.max;
    return;
  }
  // A disk of radius R with unit normal a reaches R sqrt(1 - a_i^2) along axis i.
  const Vec3d& a = reg.axis;
  const Vec3d ext(reg.radius * std::sqrt(std::max(0.0, 1 - a.x * a.x)),
                  reg.radius * std::sqrt(std::max(0.0, 1 - a.y * a.y)),
                  reg.radius * std::sqrt(std::max(0.0, 1 - a.z * a.z)));
  const Vec3d top = reg.base + reg.length * a;
  lo = Vec3d(std::min(reg.base.x, top.x), std::min(reg.base.y, top.y), std::min(reg.base.z, top.z)) - ext;
  hi = Vec3d(std::max(reg.base.x, top.x), std::max(reg.base.y, top.y), std::max(reg.base.z, top.z)) + ext;
}

FillRegion shrunk(const FillRegion& reg, double r) {
  FillRegion s = reg;
  const Vec3d d(r, r, r);
  s.min = reg.min + d;
  s.max = reg.max - d;
  s.base = reg.base + r * reg.axis;
  s.radius = reg.radius - r;
  s.length = reg.length - 2 * r;
  return s;
}

bool fits(const FillRegion& reg, double r) {
  const FillRegion s = shrunk(reg, r);
  if (reg.kind == FillRegion::Kind::cylinder) return s.radius >= 0 && s.length >= 0;
  return s.min.x <= s.max.x && s.min.y <= s.max.y && s.min.z <= s.max.z;
}

bool admits(const FillRegion& reg, const Vec3d& p, double r) {
  if (reg.kind == FillRegion::Kind::box)
    return p.x >= reg.min.x + r && p.y >= reg.min.y + r && p.z >= reg.min.z + r && p.x <= reg.max.x - r &&
           p.y <= reg.max.y - r && p.z <= reg.max.z - r;
  const Vec3d d = p - reg.base;
  const double along = dot(d, reg.axis), room = reg.radius - r;
  return along >= r && along <= reg.length - r && norm2(d - along * reg.axis) <= room * room;
}

Vec3d region_point(const FillRegion& reg, const Vec3d& u) {
  if (reg.kind == FillRegion::Kind::box)
    return Vec3d(reg.min.x + u.x * (reg.max.x - reg.min.x), reg.min.y + u.y * (reg.max.y - reg.min.y),
                 reg.min.z + u.z * (reg.max.z - reg.min.z));
  // Two unit vectors across the axis; the radius goes as sqrt(u) for a uniform disk.
  const Vec3d& a = reg.axis;
  const Vec3d helper = std::abs(a.x) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  const Vec3d across = cross(a, helper);
  const Vec3d e1 = (1.0 / norm(across)) * across, e2 = cross(a, e1);
  const double rho = reg.radius * std::sqrt(u.x), phi = 2 * M_PI * u.y;
  return reg.base + (u.z * reg.length) * a + (rho * std::cos(phi)) * e1 + (rho * std::sin(phi)) * e2;
}

std::vector<SizeClass> count_fractions_from_mass(const std::vector<SizeClass>& by_mass) {
  std::vector<SizeClass> out = by_mass;
  double total = 0;
  for (SizeClass& c : out) {
    c.fraction = c.fraction / (c.diameter * c.diameter * c.diameter);
    total += c.fraction;
  }
  for (SizeClass& c : out) c.fraction /= total;
  return out;
}

double radius_at(const SizeSpec& size, double u) {
  if (size.kind == SizeSpec::Kind::fixed) return size.radius_min;
  if (size.kind == SizeSpec::Kind::uniform) return size.radius_min + (size.radius_max - size.radius_min) * u;
  double cumulative = 0;
  for (const SizeClass& c : size.classes) {
    cumulative += c.fraction;
    if (u < cumulative) return 0.5 * c.diameter;
  }
  return 0.5 * size.classes.back().diameter;  // u beyond a sum rounded below 1
}

double largest_radius(const SizeSpec& size) {
  if (size.kind != SizeSpec::Kind::classes) return size.radius_max;
  double r = 0;
  for (const SizeClass& c : size.classes) r = std::max(r, 0.5 * c.diameter);
  return r;
}

double smallest_radius(const SizeSpec& size) {
  if (size.kind != SizeSpec::Kind::classes) return size.radius_min;
  double r = 0.5 * size.classes.front().diameter;
  for (const SizeClass& c : size.classes) r = std::min(r, 0.5 * c.diameter);
  return r;
}

double mean_particle_volume(const SizeSpec& size) {
  const double k = 4.0 / 3.0 * M_PI;
  if (size.kind == SizeSpec::Kind::fixed) return k * size.radius_min * size.radius_min * size.radius_min;
  if (size.kind == SizeSpec::Kind::uniform) {
    // E[r^3] for r uniform in [a, b]: (b^4 - a^4) / (4 (b - a)), or a^3 when a = b.
    const double a = size.radius_min, b = size.radius_max;
    if (b == a) return k * a * a * a;
    return k * (b * b * b * b - a * a * a * a) / (4 * (b - a));
  }
  double mean = 0;
  for (const SizeClass& c : size.classes) mean += c.fraction * k * std::pow(0.5 * c.diameter, 3);
  return mean;
}

}  // namespace gs
