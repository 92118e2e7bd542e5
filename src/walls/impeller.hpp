#pragma once
// Closed triangle meshes of simple solids, and the seed paper's four-bladed
// impeller built from them (Radeke et al. 2010, Table 1; cases/mixer/README.md).
#include <utility>
#include <vector>

#include "walls/triangle_mesh.hpp"

namespace gs {

// Box with orthonormal, right-handed axes (u, v, w = u x v) and half extents
// along them: 8 vertices, 12 triangles, normals outwards.
TriangleMesh make_box(const Vec3d& centre, const Vec3d& u, const Vec3d& v, const Vec3d& half_extent);

// Solid of revolution about the z axis: the closed profile (r, z) starts on
// the axis (r = 0) at the bottom, runs outwards and up with r > 0 and ends on
// the axis at the top (counter-clockwise in the r-z half plane). Each circle
// is a regular polygon of `segments` sides with its corners on the circle
// (angle 0 on +x); profile pieces longer than `max_edge` (> 0) are split.
// Normals outwards.
TriangleMesh make_revolved(const std::vector<std::pair<double, double>>& profile, int segments, double max_edge);

// The reference impeller, in metres, axis +z, hub bottom centre at the origin.
// Blade k is a flat plate (a box) along the radial direction at angle
// 90 k degrees from +x, centred at half the hub height, pitched by
// `blade_angle_deg` about its radial axis: its width direction is
// cos(angle) e_theta + sin(angle) e_z. Turning about +z with positive angular
// velocity, the blade faces that lead push the powder downwards.
struct ImpellerSpec {
  int blades = 4;
  double blade_width = 0.025;        // BW
  double blade_diameter = 0.095;     // BD: diameter swept by the outermost blade corners
  double blade_angle_deg = 45;       // BA, from the horizontal plane
  double blade_thickness = 0.002;    // not in the paper: our choice
  double blade_root_radius = 0.004;  // blades start inside the hub, so their root faces are hidden
  double hub_diameter = 0.022;       // HD
  double hub_height = 0.020;         // HH
  double shaft_diameter = 0.012;     // SD
  double shaft_length = 0.080;       // above the hub top (not in the paper)
  int segments = 64;                 // sides of the polygons of the hub and the shaft
  double max_edge = 0.005;           // longest profile piece of hub and shaft
};

// Hub and shaft as one closed shell (a stepped solid of revolution) plus one
// closed box per blade, whose roots are buried in the hub: every shell is
// closed and outward oriented; the blade roots overlap the hub, so the
// divergence-theorem volume is the sum of the parts' volumes. Throws
// std::invalid_argument when the parts would not fit (a blade root outside
// the hub, a blade taller than the hub, tips inside the hub).
TriangleMesh make_impeller(const ImpellerSpec& spec = {});

// Radial extent [root, tip] of each blade box, and its largest distance from
// its radial centre line in the horizontal plane, for a spec.
struct BladeLayout {
  double root_radius;
  double tip_radius;
  double half_span;    // horizontal half extent across the blade (width and thickness projected)
  double half_height;  // vertical half extent
};
BladeLayout blade_layout(const ImpellerSpec& spec);

}  // namespace gs
