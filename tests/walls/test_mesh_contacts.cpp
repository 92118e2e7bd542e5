// The de-duplication rule of walls/sphere_triangle.hpp: one contact per
// touching region. A tessellated flat square must act exactly as the analytic
// plane wherever the sphere is (above a face, exactly above a shared edge or a
// shared vertex, within rounding of them); a cube gives one contact at an edge
// or a corner; a concave corner gives one contact per face.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh_test_helpers.hpp"
#include "walls/impeller.hpp"

namespace gs {
namespace {

using test::all_contacts;
using test::FlatSquare;
using test::make_flat_square;
using test::Rotation;

constexpr double kRadius = 0.3;

// One contact with the overlap and normal of the analytic plane.
void expect_plane_contact(const FlatSquare& sq, const Vec3d& x, const std::string& where) {
  const MeshSet set = test::single_mesh_set(sq.mesh);
  const std::vector<MeshContact> c = all_contacts(set, x, kRadius);
  const double signed_height = dot(x - sq.origin, sq.normal);
  const double overlap = kRadius - std::fabs(signed_height);
  ASSERT_EQ(c.size(), 1u) << where << " (height " << signed_height << ")";
  EXPECT_NEAR(c[0].overlap, overlap, 1e-13) << where;
  const Vec3d n = sq.normal * (signed_height < 0 ? -1.0 : 1.0);
  // An edge or vertex normal is (x - q) / |x - q|: rounding of q (about
  // 1e-16 of the coordinates) tilts it by that over the height.
  const double scale = std::fmax(std::fabs(x.x), std::fmax(std::fabs(x.y), std::fabs(x.z)));
  const double normal_tol = 1e-12 + 4e-16 * scale / std::fabs(signed_height);
  EXPECT_NEAR(norm(c[0].normal - n), 0, normal_tol) << where << " feature " << int(c[0].feature);
  EXPECT_NEAR(norm(c[0].point - (x - n * std::fabs(signed_height))), 0, 1e-12) << where;
}

// Squares in the frame of the test, and tilted (so nothing is exact).
std::vector<FlatSquare> squares() {
  return {make_flat_square(8, 0.25, 0.0, Rotation(Vec3d(0, 0, 1), 0), Vec3d(), 1),
          make_flat_square(8, 0.25, 0.2, Rotation(Vec3d(0, 0, 1), 0), Vec3d(), 2),
          make_flat_square(8, 0.25, 0.2, Rotation(Vec3d(1, 2, 0.5), 0.7), Vec3d(0.3, -1.1, 2.9), 3),
          make_flat_square(6, 0.4, 0.25, Rotation(Vec3d(-0.3, 1, 2), 2.1), Vec3d(-5.5, 3.25, 0.125), 4)};
}

TEST(MeshContacts, FlatSquareAboveFaceEdgeAndVertex) {
  for (const FlatSquare& sq : squares()) {
    const MeshSet set = test::single_mesh_set(sq.mesh);
    for (double h : {0.1, 0.2999, -0.15, 1e-9}) {
      // Above the centroid of every triangle, the midpoint of every edge and
      // every vertex (interior and boundary), exactly as computed.
      for (const TriangleIndices& t : sq.mesh.triangles) {
        const Vec3d a = sq.local[t[0]], b = sq.local[t[1]], c = sq.local[t[2]];
        expect_plane_contact(sq, sq.to_world((a + b + c) * (1.0 / 3) + Vec3d(0, 0, h)), "face");
        expect_plane_contact(sq, sq.to_world((a + b) * 0.5 + Vec3d(0, 0, h)), "edge");
        expect_plane_contact(sq, sq.to_world(a + Vec3d(0, 0, h)), "vertex");
        if (::testing::Test::HasFailure()) return;
      }
    }
  }
}

TEST(MeshContacts, FlatSquareWithinRoundingOfEdgesAndVertices) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586);
  for (const FlatSquare& sq : squares()) {
    const double side = sq.local.back().x;
    // Points beyond the square's border touch its boundary edge, not the plane.
    auto check = [&](const Vec3d& local, const char* where) {
      if (local.x >= 0 && local.y >= 0 && local.x <= side && local.y <= side)
        expect_plane_contact(sq, sq.to_world(local), where);
    };
    for (const TriangleIndices& t : sq.mesh.triangles)
      for (double offset : {1e-17, 1e-15, 1e-13, 1e-11, 1e-8}) {
        const double phi = angle(rng);
        const Vec3d shift(offset * std::cos(phi), offset * std::sin(phi), 0.17);
        check((sq.local[t[0]] + sq.local[t[1]]) * 0.5 + shift, "near edge");
        check(sq.local[t[1]] + shift, "near vertex");
        if (::testing::Test::HasFailure()) return;
      }
  }
}

TEST(MeshContacts, FlatSquareRandomPositionsGiveThePlaneForce) {
  std::mt19937_64 rng(5);
  for (const FlatSquare& sq : squares()) {
    const double side = sq.local.back().x;
    std::uniform_real_distribution<double> in(0.02 * side, 0.98 * side), height(-0.99 * kRadius, 0.99 * kRadius);
    for (int i = 0; i < 3000; ++i) {
      expect_plane_contact(sq, sq.to_world(Vec3d(in(rng), in(rng), height(rng))), "random");
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(MeshContacts, NoContactOutOfReach) {
  const FlatSquare sq = squares()[2];
  const MeshSet set = test::single_mesh_set(sq.mesh);
  EXPECT_TRUE(all_contacts(set, sq.to_world(Vec3d(1, 1, kRadius * 1.0001)), kRadius).empty());
  EXPECT_TRUE(all_contacts(set, sq.to_world(Vec3d(-0.31, 1, 0)), kRadius).empty());
}

TEST(MeshContacts, HighValenceFan) {
  // 48 triangles around one vertex (a disk fan): above the centre, and near it.
  TriangleMeshBuilder b("fan");
  const int n = 48;
  const std::int32_t centre = b.vertex(Vec3d(0, 0, 0));
  for (int j = 0; j < n; ++j) {
    const double p0 = 6.283185307179586 * j / n, p1 = 6.283185307179586 * ((j + 1) % n) / n;  // closed fan
    b.triangle(centre, b.vertex(Vec3d(std::cos(p0), std::sin(p0), 0)), b.vertex(Vec3d(std::cos(p1), std::sin(p1), 0)));
  }
  const MeshSet set = test::single_mesh_set(b.take());
  // Near the centre every triangle is within reach (more than kMeshInReachCap:
  // the whole list is scanned); further out a few are (only they are).
  bool few = false, many = false;
  for (double r : {0.0, 1e-14, 1e-9, 1e-3, 0.05, 0.25, 0.3, 0.4, 0.7})
    for (int k = 0; k < 17; ++k) {
      const double phi = 0.37 * k;
      const Vec3d x(r * std::cos(phi), r * std::sin(phi), 0.2);
      int in_reach = 0;
      for (std::int32_t t = 0; t < n; ++t) in_reach += triangle_closest_point(set.view(), t, x).distance < kRadius;
      (in_reach > kMeshInReachCap ? many : few) = true;
      const std::vector<MeshContact> c = all_contacts(set, x, kRadius);
      ASSERT_EQ(c.size(), 1u) << "r " << r << " phi " << phi;
      EXPECT_NEAR(c[0].overlap, 0.1, 1e-15);
      EXPECT_NEAR(norm(c[0].normal - Vec3d(0, 0, 1)), 0, 1e-15);
    }
  EXPECT_TRUE(few && many);
}

// Spheres of mixer case b (1.05 mm) wedged under the reference impeller's hub,
// whose bottom is a fan of 64 triangles around the axis, at 0 to 3 mm from
// it, with the triangles within three radii as their cell's list.
std::vector<Vec3d> spheres_under_the_hub() {
  std::vector<Vec3d> x;
  for (double r : {0.0, 2e-5, 9e-5, 4.6e-4, 1e-3, 1.5e-3, 3e-3})
    for (int k = 0; k < 7; ++k) x.push_back(Vec3d(r * std::cos(0.9 * k + 0.1), r * std::sin(0.9 * k + 0.1), -1e-3));
  return x;
}
std::vector<std::int32_t> cell_list(const MeshView& m, std::int32_t n, const Vec3d& x, double reach) {
  std::vector<std::int32_t> list;
  for (std::int32_t t = 0; t < n; ++t)
    if (triangle_closest_point(m, t, x).distance < reach) list.push_back(t);
  return list;
}

// The rule asks the nearest report's triangle first (NearestReport): the
// contacts are those of the rule asking the list in its order.
TEST(MeshContacts, NearestReportFirstKeepsTheContacts) {
  const MeshSet set = test::single_mesh_set(make_impeller());
  const MeshView m = set.view();
  const double radius = 1.05e-3;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-1.2 * radius, 1.2 * radius);
  std::vector<Vec3d> spheres = spheres_under_the_hub();
  for (int q = 0; q < 200; ++q) {  // and near the blades, hub and shaft
    const MeshCorners& c = set.corners[std::size_t(q * 7919 % set.n_triangles())];
    spheres.push_back((set.vertex[std::size_t(c.v[0])] + set.vertex[std::size_t(c.v[1])] +
                       set.vertex[std::size_t(c.v[2])]) * (1.0 / 3) + Vec3d(offset(rng), offset(rng), offset(rng)));
  }
  int contacts = 0, beyond_cap = 0;
  for (const Vec3d& x : spheres) {
    const std::vector<std::int32_t> list = cell_list(m, set.n_triangles(), x, 3 * radius);
    const std::int32_t n = std::int32_t(list.size());
    std::vector<MeshContact> found;
    auto collect = [&](const MeshContact& c) { found.push_back(c); };
    for_each_mesh_contact_in(m, list.data(), n, x, radius, collect);
    const double tol = mesh_coincidence_tolerance(x, radius);
    std::vector<std::int32_t> in_order;  // the rule, asking the whole list in order
    int in_reach = 0;
    for (std::int32_t t : list) {
      const ClosestPoint r = triangle_closest_point(m, t, x);
      in_reach += r.distance < radius;
      if (mesh_report_kept(m, list.data(), n, x, radius, tol * tol, t, r, -1)) in_order.push_back(t);
    }
    beyond_cap += in_reach > kMeshInReachCap;
    ASSERT_EQ(found.size(), in_order.size()) << "sphere at " << x.x << " " << x.y << " " << x.z;
    for (std::size_t k = 0; k < found.size(); ++k) EXPECT_EQ(found[k].triangle, in_order[k]);
    contacts += int(found.size());
  }
  EXPECT_GT(contacts, 150);
  EXPECT_GT(beyond_cap, 0);  // the scan of the whole list too
}

// Why asking the nearest report first pays: under the hub's fan the nearest
// report alone drops every other report in reach, so each costs one closest
// point, not a scan of the 64 to 100 triangles of its cell.
TEST(MeshContacts, UnderAFanTheNearestReportDropsTheOthers) {
  const MeshSet set = test::single_mesh_set(make_impeller());
  const MeshView m = set.view();
  const double radius = 1.05e-3;
  int dropped = 0;
  for (const Vec3d& x : spheres_under_the_hub()) {
    const std::vector<std::int32_t> list = cell_list(m, set.n_triangles(), x, 3 * radius);
    NearestReport first;
    for (std::int32_t t : list) {
      const ClosestPoint r = triangle_closest_point(m, t, x);
      if (r.distance < radius) first.consider(r.distance, r.feature, t);
    }
    const std::int32_t nearest = first.t;
    ASSERT_GE(nearest, 0);
    const double tol = mesh_coincidence_tolerance(x, radius);
    for (std::int32_t t : list) {
      const ClosestPoint r = triangle_closest_point(m, t, x);
      if (t == nearest || !(r.distance < radius)) continue;
      EXPECT_TRUE(detail::objects(m, x, radius, tol * tol, detail::make_report(m, t, r), nearest))
          << "triangle " << t << " under the hub at " << x.x << " " << x.y;
      ++dropped;
    }
  }
  EXPECT_GT(dropped, 7 * 64);  // the spheres at the axis see the whole fan
}

TEST(MeshContacts, ConvexCubeEdgesAndCorners) {
  const MeshSet set = test::single_mesh_set(make_box(Vec3d(), Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(0.5, 0.5, 0.5)));
  struct Case {
    Vec3d x;
    int rank;  // expected feature rank: 0 face, 1 edge, 2 vertex
    double distance;
    Vec3d normal;
  };
  const double s2 = std::sqrt(0.5), s3 = std::sqrt(1.0 / 3);
  const Case cases[] = {
      {{0.6, 0.1, -0.2}, 0, 0.1, {1, 0, 0}},                       // face
      {{0.6, 0.2, 0.2}, 1, 0.1, {1, 0, 0}},                        // on the face's own diagonal
      {{0.6, 0.5, 0.0}, 1, 0.1, {1, 0, 0}},                        // on the boundary of an edge region
      {{0.6, 0.6, 0.0}, 1, std::sqrt(0.02), {s2, s2, 0}},          // edge
      {{0.6, 0.6, 0.5}, 2, std::sqrt(0.02), {s2, s2, 0}},          // edge end = corner, seen from the edge region
      {{0.6, 0.6, 0.6}, 2, std::sqrt(0.03), {s3, s3, s3}},         // corner
      {{-0.58, -0.61, -0.57}, 2, std::sqrt(0.0234), {-0.08, -0.11, -0.07}},
  };
  for (const Case& k : cases) {
    const std::vector<MeshContact> c = all_contacts(set, k.x, kRadius);
    ASSERT_EQ(c.size(), 1u) << k.x.x << " " << k.x.y << " " << k.x.z;
    EXPECT_NEAR(c[0].overlap, kRadius - k.distance, 1e-14);
    const Vec3d n = k.normal * (1.0 / norm(k.normal));
    EXPECT_NEAR(norm(c[0].normal - n), 0, 1e-14);
    EXPECT_LE(feature_rank(c[0].feature), 2);
    if (k.rank == 1 && k.distance > 0.1) {
      EXPECT_EQ(feature_rank(c[0].feature), 1);
    }
    if (k.rank == 2 && k.distance > 0.15) {
      EXPECT_EQ(feature_rank(c[0].feature), 2);
    }
  }
}

TEST(MeshContacts, ConcaveCornerGivesOneContactPerFace) {
  // Floor z = 0 and wall x = 0 meeting along the y axis (shared vertices).
  TriangleMeshBuilder b("corner");
  const std::int32_t o0 = b.vertex({0, 0, 0}), o1 = b.vertex({0, 1, 0});
  const std::int32_t f0 = b.vertex({1, 0, 0}), f1 = b.vertex({1, 1, 0});
  const std::int32_t w0 = b.vertex({0, 0, 1}), w1 = b.vertex({0, 1, 1});
  b.quad(o0, f0, f1, o1);  // floor, normal +z
  b.quad(o0, o1, w1, w0);  // wall, normal +x
  const MeshSet set = test::single_mesh_set(b.take());
  for (double y : {0.5, 0.25, 0.4}) {  // 0.25: on the wall's diagonal
    const std::vector<MeshContact> c = all_contacts(set, Vec3d(0.1, y, 0.25), kRadius);
    ASSERT_EQ(c.size(), 2u);
    double floor = 0, wall = 0;
    for (const MeshContact& k : c) {
      if (norm(k.normal - Vec3d(0, 0, 1)) < 1e-14) floor = k.overlap;
      if (norm(k.normal - Vec3d(1, 0, 0)) < 1e-14) wall = k.overlap;
    }
    EXPECT_NEAR(floor, 0.05, 1e-14);
    EXPECT_NEAR(wall, 0.2, 1e-14);
  }
  // In the corner's bisector, above the shared edge: still one contact per face.
  EXPECT_EQ(all_contacts(set, Vec3d(0.2, 0.5, 0.2), kRadius).size(), 2u);
}

TEST(MeshContacts, ConvexBodyAlwaysOneContactAtTheClosestPoint) {
  // Outside a convex polyhedron the distance has one local minimum: whatever
  // the feature (random points around vertices, edges and faces, some within
  // rounding of them), exactly one contact at the true distance.
  const TriangleMesh m = make_revolved({{0, 0}, {0.6, 0.1}, {1, 0.5}, {1, 1.5}, {0.7, 1.9}, {0, 2}}, 24, 0.3);
  const MeshSet set = test::single_mesh_set(m);
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u01(0, 1);
  const double r = 0.2;
  int touching = 0;
  for (int i = 0; i < 6000; ++i) {
    const TriangleIndices& t = m.triangles[pick(rng)];
    const Vec3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const double s = u01(rng), w = u01(rng);
    const Vec3d q = i % 3 == 0 ? a : (i % 3 == 1 ? a + (b - a) * s : a + (b - a) * (s * (1 - w)) + (c - a) * (s * w));
    Vec3d dir(g(rng), g(rng), g(rng));
    const Vec3d x = q + dir * (u01(rng) * 1.2 * r / norm(dir)) + Vec3d(g(rng), g(rng), g(rng)) * (i % 2 ? 1e-15 : 0.0);
    bool inside = true;  // behind every face (outward normals)
    double closest = 1e300;
    for (const TriangleIndices& u : m.triangles) {
      const Vec3d ua = m.vertices[u[0]];
      inside = inside && dot(cross(m.vertices[u[1]] - ua, m.vertices[u[2]] - ua), x - ua) < 0;
      closest = std::min(closest, closest_point_on_triangle(x, ua, m.vertices[u[1]], m.vertices[u[2]]).distance);
    }
    if (inside || !(closest < r)) continue;
    const std::vector<MeshContact> contacts = all_contacts(set, x, r);
    ASSERT_EQ(contacts.size(), 1u) << x.x << " " << x.y << " " << x.z;
    EXPECT_NEAR(r - contacts[0].overlap, closest, 1e-15);
    ++touching;
  }
  EXPECT_GT(touching, 2500);
}

TEST(MeshContacts, TessellatedCylinderFromInside) {
  // A vessel of 48 flat sides, seen from inside: in the thin wedge over a
  // crease both sides are within reach; rule F keeps the nearer one. At the
  // 90 degree corner with the floor, two contacts.
  const MeshSet set = test::single_mesh_set(make_revolved({{0, 0}, {0.05, 0}, {0.05, 0.08}, {0, 0.08}}, 48, 0.02));
  const double r = 0.0015, R = 0.05, half = 3.14159265358979323846 / 48;
  for (double off : {-1e-3, -1e-6, 0.0, 1e-6, 1e-3}) {
    // Near the crease at angle 2 half (a vertex column), 1 mm from the wall.
    const double phi = 2 * half + off, rho = R * std::cos(half) - 0.001;
    for (double z : {0.04, 0.05}) {  // on a ring of horizontal edges, and between rings
      const std::vector<MeshContact> c = all_contacts(set, Vec3d(rho * std::cos(phi), rho * std::sin(phi), z), r);
      ASSERT_EQ(c.size(), 1u) << off << " " << z;
    }
  }
  // Mid-facet, 1.39 mm from the side and 1 mm above the floor.
  EXPECT_EQ(all_contacts(set, Vec3d(0.0485 * std::cos(half), 0.0485 * std::sin(half), 0.001), r).size(), 2u);
}

TEST(MeshContacts, OpenBoundaryCorner) {
  const FlatSquare sq = squares()[1];
  const MeshSet set = test::single_mesh_set(sq.mesh);
  const std::vector<MeshContact> c = all_contacts(set, Vec3d(-0.1, -0.1, 0.1), kRadius);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(feature_rank(c[0].feature), 2);
  EXPECT_NEAR(c[0].overlap, kRadius - std::sqrt(0.03), 1e-15);
}

TEST(MeshContacts, RollingContactMovesBetweenAdjacentFeatures) {
  // Along a path over a tilted, jittered floor, consecutive contacts are on
  // the same feature or on features sharing a vertex: friction history can
  // follow the contact from triangle to triangle.
  const FlatSquare sq = squares()[2];
  const MeshSet set = test::single_mesh_set(sq.mesh);
  const MeshView v = set.view();
  std::uint32_t previous = 0;
  int changes = 0;
  for (int s = 0; s <= 4000; ++s) {
    const double f = s / 4000.0;
    const Vec3d x = sq.to_world(Vec3d(0.1 + 1.7 * f, 0.3 + 1.1 * f + 0.2 * std::sin(9 * f), 0.28));
    const std::vector<MeshContact> c = all_contacts(set, x, kRadius);
    ASSERT_EQ(c.size(), 1u);
    if (s > 0 && c[0].feature_key != previous) {
      ++changes;
      EXPECT_TRUE(mesh_features_adjacent(v, previous, c[0].feature_key)) << "step " << s;
    }
    previous = c[0].feature_key;
  }
  EXPECT_GT(changes, 10);
}

TEST(MeshContacts, FeatureKeysNameTheFeatureNotTheReporter) {
  // Both triangles of a shared edge give the same key for it.
  const FlatSquare sq = squares()[0];
  const MeshSet set = test::single_mesh_set(sq.mesh);
  const MeshView v = set.view();
  for (std::int32_t t = 0; t < set.n_triangles(); ++t)
    for (std::int32_t u = 0; u < set.n_triangles(); ++u)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const bool same_edge = set.edges[t].e[i] == set.edges[u].e[j];
          EXPECT_EQ(same_edge, mesh_feature_key(v, t, std::uint8_t(kEdge0 + i)) ==
                                   mesh_feature_key(v, u, std::uint8_t(kEdge0 + j)));
          const bool same_vertex = set.corners[t].v[i] == set.corners[u].v[j];
          EXPECT_EQ(same_vertex, mesh_feature_key(v, t, std::uint8_t(kVertex0 + i)) ==
                                     mesh_feature_key(v, u, std::uint8_t(kVertex0 + j)));
        }
}

}  // namespace
}  // namespace gs
