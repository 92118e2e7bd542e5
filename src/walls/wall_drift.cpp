#include "walls/wall_drift.hpp"

#include <algorithm>
#include <cmath>

namespace gs {

double wall_displacement_bound(const Wall& from, const Wall& to, const Vec3d& lo, const Vec3d& hi) {
  // A point y of the box, fixed to the wall, goes to M (y - c) + c + to.shift
  // with M = R_to R_from^T and c = axis_point + from.shift: it moves by
  // (M - I)(y - c) + (to.shift - from.shift).
  double stretch2 = 0;  // |M - I|_F^2
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      double m = 0;
      for (int j = 0; j < 3; ++j) m += to.rotation[3 * r + j] * from.rotation[3 * k + j];
      const double e = m - (r == k ? 1.0 : 0.0);
      stretch2 += e * e;
    }
  const Vec3d c = from.axis_point + from.shift;
  double reach = 0;  // the farthest corner from c (|y - c| is convex, so a corner)
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3d y{(corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z};
    reach = std::max(reach, norm(y - c));
  }
  return std::sqrt(stretch2) * reach + norm(to.shift - from.shift);
}

bool WallDrift::beyond(const std::vector<Wall>& walls, double allowed) const {
  if (built_at_.size() != walls.size()) return true;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (walls[w].active != built_at_[w].active) return true;
    if (!walls[w].active) continue;
    if (!(wall_displacement_bound(built_at_[w], walls[w], lo_, hi_) <= allowed)) return true;
  }
  return false;
}

}  // namespace gs
