// The reference impeller mesh (tools/make_impeller): closed, consistently
// oriented shells whose divergence-theorem volume matches the analytic volume
// of the parts, with the dimensions of the seed paper's Table 1.
#include <gtest/gtest.h>

#include <cmath>

#include "walls/impeller.hpp"

namespace gs {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Volume of the parts: polygonal cylinders with `segments` sides (corners on
// the circle) when exact_polygons, true circles otherwise, plus the boxes.
double parts_volume(const ImpellerSpec& s, bool exact_polygons) {
  const double circle = exact_polygons ? 0.5 * s.segments * std::sin(2 * kPi / s.segments) : kPi;
  const double hub = circle * std::pow(0.5 * s.hub_diameter, 2) * s.hub_height;
  const double shaft = circle * std::pow(0.5 * s.shaft_diameter, 2) * s.shaft_length;
  const BladeLayout l = blade_layout(s);
  const double blade = (l.tip_radius - l.root_radius) * s.blade_width * s.blade_thickness;
  return hub + shaft + s.blades * blade;
}

TEST(Impeller, ClosedAndConsistentlyOriented) {
  const TriangleMesh m = make_impeller();
  const MeshTopology t = mesh_topology(m);
  EXPECT_EQ(t.boundary_edges, 0u);
  EXPECT_EQ(t.non_manifold_edges, 0u);
  EXPECT_EQ(t.misoriented_edges, 0u);
  // Euler characteristic: five closed shells of genus 0 (hub with shaft, four blades).
  EXPECT_EQ(std::int64_t(m.vertices.size()) - std::int64_t(t.edges) + std::int64_t(m.triangles.size()), 2 * 5);
  validate_mesh(m, "impeller");
}

TEST(Impeller, VolumeMatchesTheParts) {
  for (int segments : {64, 256}) {
    ImpellerSpec s;
    s.segments = segments;
    const double v = mesh_volume(make_impeller(s));
    // Exact for the polygonal solids the mesh describes (rounding only).
    EXPECT_NEAR(v / parts_volume(s, true), 1.0, 1e-12) << segments;
    // Against true cylinders the polygons lose 1 - sin(2 pi/N)/(2 pi/N) of
    // the round parts' volume: 0.16 % at N = 64, 0.01 % at N = 256.
    const double deficit = 1 - std::sin(2 * kPi / segments) / (2 * kPi / segments);
    EXPECT_NEAR(v / parts_volume(s, false), 1.0, 1.05 * deficit) << segments;
    EXPECT_LT(v, parts_volume(s, false));
  }
}

TEST(Impeller, DimensionsOfTheReferenceDevice) {
  const ImpellerSpec s;
  const TriangleMesh m = make_impeller(s);
  Vec3d lo, hi;
  mesh_bounds(m, lo, hi);
  EXPECT_NEAR(lo.z, 0, 1e-15);
  EXPECT_NEAR(hi.z, 0.100, 1e-15);
  double swept = 0, hub = 0;
  for (const Vec3d& x : m.vertices) {
    const double r = std::hypot(x.x, x.y);
    swept = std::max(swept, r);
    if (x.z <= 0) hub = std::max(hub, r);
  }
  EXPECT_NEAR(2 * swept, 0.095, 1e-12);  // blade diameter BD
  EXPECT_NEAR(2 * hub, 0.022, 1e-15);    // hub diameter HD
  // Blades: 45 degrees, inside the hub height, 2.4 mm clear of the 100 mm vessel.
  const BladeLayout l = blade_layout(s);
  EXPECT_LT(2 * l.half_height, s.hub_height);
  EXPECT_GT(0.050 - swept, 0.0024);
  EXPECT_THROW(make_impeller([] {
                 ImpellerSpec bad;
                 bad.blade_root_radius = 0.009;
                 return bad;
               }()),
               std::invalid_argument);
}

}  // namespace
}  // namespace gs
