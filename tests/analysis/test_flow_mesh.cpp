// Flow through a triangle mesh (analysis/flow_mesh.hpp) against what is
// known exactly: a square of two triangles counts every crossing a flat
// rectangle of the same extent counts (the same segments, one by one,
// including paths exactly through the shared diagonal), and a closed cube's
// net count of a path is its change of inside (paths through its edges and
// vertices included).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "analysis/flow_measure.hpp"

namespace gs::test {
namespace {

// A fixed sequence of numbers in [0, 1) (SplitMix64): the same on every platform.
class Draws {
 public:
  double next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  Vec3d in(const Vec3d& lo, const Vec3d& hi) {
    const double x = next(), y = next(), z = next();
    return {lo.x + x * (hi.x - lo.x), lo.y + y * (hi.y - lo.y), lo.z + z * (hi.z - lo.z)};
  }

 private:
  std::uint64_t state_ = 12345;
};

// The rectangle [0.25, 0.75] x [0.375, 0.625] at z = 0.5, counting downwards.
FlowSpec rectangle_down() {
  FlowSpec f;
  f.name = "rectangle";
  f.point = {0.5, 0.5, 0.5};
  f.normal = {0, 0, -1};
  f.bound = FlowBound::rectangle;
  f.axis_u = {1, 0, 0};
  f.axis_v = cross(f.normal, f.axis_u);
  f.half_length_u = 0.25;
  f.half_length_v = 0.125;
  return f;
}

// The same rectangle as two triangles wound so that their normal is -z.
FlowSpec square_mesh_down() {
  FlowSpec f;
  f.name = "square";
  f.bound = FlowBound::mesh;
  TriangleMeshBuilder b("square");
  const Vec3d a{0.25, 0.375, 0.5}, c{0.75, 0.625, 0.5};
  const Vec3d corner_b{0.25, 0.625, 0.5}, corner_d{0.75, 0.375, 0.5};
  b.triangle(a, corner_b, c);  // (b - a) x (c - a) points along -z
  b.triangle(a, c, corner_d);
  f.surface = b.take();
  return f;
}

ParticleSnapshot particles(const std::vector<Vec3d>& positions, double time) {
  ParticleSnapshot s;
  s.time = time;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    s.id.push_back(ParticleId(i));
    s.position.push_back(positions[i]);
    s.mass.push_back(1e-6f * float(1 + i % 7));
    s.material.push_back(0);
    s.marker.push_back(0);
  }
  return s;
}

TEST(FlowMesh, SquareOfTwoTrianglesCountsWhatTheRectangleCounts) {
  Draws draws;
  std::vector<Vec3d> before, after;
  for (int i = 0; i < 20000; ++i) {
    before.push_back(draws.in({0.1, 0.2, 0.3}, {0.9, 0.8, 0.7}));
    after.push_back(draws.in({0.1, 0.2, 0.3}, {0.9, 0.8, 0.7}));
  }
  // Vertical paths exactly through the shared diagonal (dyadic coordinates:
  // every volume is exact, so these are the zero volumes the shift decides)
  // and through the square's centre, downwards and upwards.
  for (int k = 1; k < 8; ++k) {
    const Vec3d on{0.25 + 0.5 * k / 8, 0.375 + 0.25 * k / 8, 0.5};
    before.push_back(on + Vec3d(0, 0, 0.25));
    after.push_back(on - Vec3d(0, 0, 0.25));
    before.push_back(on - Vec3d(0, 0, 0.125));
    after.push_back(on + Vec3d(0, 0, 0.125));
  }
  const FlowSpec rectangle = rectangle_down(), square = square_mesh_down();
  const FlowMeshSurface surface(square.surface);
  long long crossings = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const int expected = flow_crossing(rectangle, before[i], after[i]);
    const FlowCrossings c = surface.crossings(before[i], after[i]);
    ASSERT_EQ(c.forward, expected > 0 ? 1 : 0) << "path " << i;
    ASSERT_EQ(c.backward, expected < 0 ? 1 : 0) << "path " << i;
    crossings += expected != 0;
  }
  EXPECT_GT(crossings, 1000);
  // Through the counters: the same tallies, masses to the bit.
  FlowCounter by_rectangle(rectangle, {"glass"}), by_square(square, {"glass"});
  for (FlowCounter* counter : {&by_rectangle, &by_square}) {
    counter->update(particles(before, 0));
    counter->update(particles(after, 0.01));
  }
  for (std::size_t g = 0; g < by_square.groups().size(); ++g) {
    const FlowTally &r = by_rectangle.groups()[g].cumulative, &m = by_square.groups()[g].cumulative;
    EXPECT_EQ(m.forward, r.forward);
    EXPECT_EQ(m.backward, r.backward);
    EXPECT_EQ(m.forward_mass, r.forward_mass);
    EXPECT_EQ(m.backward_mass, r.backward_mass);
  }
}

// The cube [0.25, 0.75]^3 as 12 triangles, normals outwards.
TriangleMesh cube() {
  TriangleMeshBuilder b("cube");
  const Vec3d centre{0.5, 0.5, 0.5};
  auto corner = [](int i, int j, int k) { return Vec3d(0.25 + 0.5 * i, 0.25 + 0.5 * j, 0.25 + 0.5 * k); };
  auto outward = [&](const Vec3d& a, const Vec3d& c1, const Vec3d& c2) {
    const Vec3d n = cross(c1 - a, c2 - a);
    if (dot(n, a + c1 + c2 - centre * 3.0) > 0)
      b.triangle(a, c1, c2);
    else
      b.triangle(a, c2, c1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      Vec3d q[4];
      for (int m = 0; m < 4; ++m) {
        const int u = m == 1 || m == 2, v = m >= 2;
        q[m] = axis == 0 ? corner(side, u, v) : axis == 1 ? corner(u, side, v) : corner(u, v, side);
      }
      outward(q[0], q[1], q[2]);
      outward(q[0], q[2], q[3]);
    }
  return b.take();
}

bool inside_cube(const Vec3d& x) {
  return x.x > 0.25 && x.x < 0.75 && x.y > 0.25 && x.y < 0.75 && x.z > 0.25 && x.z < 0.75;
}

TEST(FlowMesh, ClosedCubeNetCountIsTheChangeOfInside) {
  const TriangleMesh mesh = cube();
  ASSERT_TRUE(mesh_topology(mesh).closed());
  ASSERT_GT(mesh_volume(mesh), 0);  // normals outwards
  const FlowMeshSurface surface(mesh);
  Draws draws;
  long long changes = 0, through = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3d p = draws.in({0, 0, 0}, {1, 1, 1}), q = draws.in({0, 0, 0}, {1, 1, 1});
    const FlowCrossings c = surface.crossings(p, q);
    // Outwards is from the back to the front: +1.
    ASSERT_EQ(c.forward - c.backward, int(inside_cube(p)) - int(inside_cube(q))) << "path " << i;
    changes += inside_cube(p) != inside_cube(q);
    through += !inside_cube(p) && !inside_cube(q) && c.forward == 1 && c.backward == 1;
  }
  EXPECT_GT(changes, 1000);
  EXPECT_GT(through, 1000);  // in and out again: one crossing each way, net zero
  // Exactly through a vertex, through two opposite vertices, along a face's
  // diagonal into an edge, through the middle of an edge.
  struct Path {
    Vec3d p, q;
    int forward, backward;
  };
  const Path paths[] = {
      {{0, 0, 0}, {0.5, 0.5, 0.5}, 0, 1},
      {{0.5, 0.5, 0.5}, {0, 0, 0}, 1, 0},
      {{0, 0, 0}, {1, 1, 1}, 1, 1},
      {{0.5, 0, 0}, {0.5, 0.5, 0.5}, 0, 1},
      {{0.5, 0.5, 0.5}, {0.5, 1, 1}, 1, 0},
      {{0.75, 0.5, 0.5}, {1, 0.5, 0.5}, 0, 0},  // from a face (its front: outside) outwards
  };
  for (const Path& path : paths) {
    const FlowCrossings c = surface.crossings(path.p, path.q);
    EXPECT_EQ(c.forward, path.forward) << "path from " << path.p.x << " " << path.p.y << " " << path.p.z;
    EXPECT_EQ(c.backward, path.backward) << "path from " << path.p.x << " " << path.p.y << " " << path.p.z;
  }
}

}  // namespace
}  // namespace gs::test
