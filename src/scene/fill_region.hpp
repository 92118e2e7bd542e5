#pragma once
// Where generated particles go and how big they are: the region and the size
// distribution shared by the random fill (scene/generators.hpp) and the
// inlets (scene/inlet_spec.hpp).
#include <vector>

#include "core/vec3.hpp"

namespace gs {

// Region a random fill or an inlet places particles in: an axis-aligned box
// or a cylinder (a disk when short).
struct FillRegion {
  enum class Kind { box, cylinder } kind = Kind::box;
  Vec3d min, max;     // box
  Vec3d base, axis;   // cylinder: centre of the base circle, unit axis
  double radius = 0;  // cylinder radius [m]
  double length = 0;  // cylinder length along the axis [m]
};

double region_volume(const FillRegion& region);
// Axis-aligned bounding box of a region.
void region_bounds(const FillRegion& region, Vec3d& lo, Vec3d& hi);
// The centres that keep a sphere of radius r inside the region: the region shrunk by r.
FillRegion shrunk(const FillRegion& region, double r);
// Whether a sphere of radius r fits in the region at all.
bool fits(const FillRegion& region, double r);
// Is p a centre that keeps a sphere of radius r inside the region?
bool admits(const FillRegion& region, const Vec3d& p, double r);
// The point of the region at uniform coordinates u (each in [0, 1)): uniform
// u gives points uniform over the region's volume.
Vec3d region_point(const FillRegion& region, const Vec3d& u);

// One diameter of a discrete size distribution and its share of the count.
struct SizeClass {
  double diameter = 0;
  double fraction = 0;
};

// How the radii of generated particles are chosen.
struct SizeSpec {
  enum class Kind { fixed, uniform, classes } kind = Kind::fixed;
  double radius_min = 0, radius_max = 0;  // fixed: both equal; uniform: range [m]
  std::vector<SizeClass> classes;         // fractions of the count, summing to 1
};

// Count fractions of classes given by mass fraction (one material): a class's
// count goes as its mass share over its particle mass, w / d^3.
std::vector<SizeClass> count_fractions_from_mass(const std::vector<SizeClass>& by_mass);
// The radius of one particle drawn at the uniform number u in [0, 1):
// uniform in [min, max], or the class whose cumulative count fraction passes u.
double radius_at(const SizeSpec& size, double u);
double largest_radius(const SizeSpec& size);
// Mean volume of one particle [m^3], by count.
double mean_particle_volume(const SizeSpec& size);
double smallest_radius(const SizeSpec& size);

}  // namespace gs
