#include "scene/position_resolution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "scene/particle_sources.hpp"

namespace gs {

double fp32_spacing(double x) {
  const float f = float(std::fabs(x));
  return double(std::nextafter(f, std::numeric_limits<float>::infinity())) - double(f);
}

std::string fp32_state_problem(const SceneSpec& scene) {
  const double r_min = smallest_radius(scene);  // inlets' particles included
  if (!fp32_state(scene.precision) || !std::isfinite(r_min)) return "";
  double far = 0;
  for (const Vec3d& c : {scene.domain_min, scene.domain_max})
    far = std::max({far, std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
  const double spacing = fp32_spacing(far);
  if (spacing <= kFp32SpacingOfRadius * r_min) return "";
  std::ostringstream m;
  m.precision(3);
  m << "precision fp32_full: fp32 positions are " << spacing << " m apart at " << far
    << " m from the origin (the domain's farthest corner), more than " << kFp32SpacingOfRadius
    << " of the smallest radius " << r_min << " m; use fp32 (fp64 positions) or move the origin into the bed";
  return m.str();
}

}  // namespace gs
