// for_each_mesh_contact_in_group (walls/sphere_triangle_group.hpp), which a
// GPU runs with a group of lanes per sphere, must find the contacts that
// for_each_mesh_contact_in finds on one thread, in the same order and with
// the same bits. Here threads play the lanes (support/thread_lanes.hpp), so
// any group size runs the algorithm as the GPU would.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "mesh_test_helpers.hpp"
#include "support/thread_lanes.hpp"
#include "walls/impeller.hpp"
#include "walls/sphere_triangle_group.hpp"

namespace gs {
namespace {

// The contacts of the sphere (x, radius) with list[0..count), found by a group
// of `lanes` threads; what lane 0 visits.
std::vector<MeshContact> group_contacts(const MeshView& m, const std::vector<std::int32_t>& list, const Vec3d& x,
                                        double radius, int lanes) {
  std::vector<MeshContact> out;
  test::run_lanes(lanes, [&](const test::ThreadLane& lane) {
    auto collect = [&](const MeshContact& c) {
      EXPECT_TRUE(lane.leader()) << "lane " << lane.rank << " visited a contact";
      out.push_back(c);
    };
    for_each_mesh_contact_in_group(m, list.data(), std::int32_t(list.size()), x, radius, lane, collect);
  });
  return out;
}

// The same bits: the contact's triangle, feature, overlap, normal, point.
bool same_contact(const MeshContact& a, const MeshContact& b) {
  return a.triangle == b.triangle && a.feature == b.feature && a.feature_key == b.feature_key && a.mesh == b.mesh &&
         std::memcmp(&a.overlap, &b.overlap, sizeof a.overlap) == 0 &&
         std::memcmp(&a.normal, &b.normal, sizeof a.normal) == 0 &&
         std::memcmp(&a.point, &b.point, sizeof a.point) == 0;
}

// Spheres of the mixer's size (1.5 mm) placed within 1.2 radii of the
// reference impeller: a third at its vertex of highest valence (the centre of
// a fan of triangles, where more than kMeshInReachCap are in reach), the
// others near random points of its faces; each against the triangles within
// three radii of it, ascending, as a cell's list holds them; groups of 1 to 32
// lanes against one thread.
TEST(MeshContactsGroup, LanesFindTheContactsOfOneThread) {
  const MeshSet set = test::single_mesh_set(make_impeller());
  const MeshView m = set.view();
  const double radius = 0.0015;
  std::vector<int> valence(set.vertex.size());
  for (const MeshCorners& c : set.corners)
    for (int k = 0; k < 3; ++k) ++valence[std::size_t(c.v[k])];
  const Vec3d hub = set.vertex[std::size_t(std::max_element(valence.begin(), valence.end()) - valence.begin())];
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1), offset(-1.2 * radius, 1.2 * radius);
  std::uniform_int_distribution<std::int32_t> triangle(0, set.n_triangles() - 1);
  int contacts = 0, capped = 0, queries = 0;
  for (int q = 0; q < 150; ++q) {
    Vec3d x = hub;
    if (q % 3 != 0) {
      const MeshCorners& c = set.corners[std::size_t(triangle(rng))];
      double a = unit(rng), b = unit(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec3d& p0 = set.vertex[std::size_t(c.v[0])];
      x = p0 + (set.vertex[std::size_t(c.v[1])] - p0) * a + (set.vertex[std::size_t(c.v[2])] - p0) * b;
    }
    x += Vec3d(offset(rng), offset(rng), offset(rng));
    std::vector<std::int32_t> list;
    int in_reach = 0;
    for (std::int32_t t = 0; t < set.n_triangles(); ++t) {
      const double d = triangle_closest_point(m, t, x).distance;
      if (d < 3 * radius) list.push_back(t);
      in_reach += d < radius;
    }
    std::vector<MeshContact> one;
    auto collect = [&](const MeshContact& c) { one.push_back(c); };
    for_each_mesh_contact_in(m, list.data(), std::int32_t(list.size()), x, radius, collect);
    ++queries;
    contacts += int(one.size());
    capped += in_reach > kMeshInReachCap;
    for (int lanes : {1, 2, 4, 8, 16, 32}) {
      const std::vector<MeshContact> group = group_contacts(m, list, x, radius, lanes);
      ASSERT_EQ(group.size(), one.size()) << lanes << " lanes, sphere " << q;
      for (std::size_t k = 0; k < one.size(); ++k)
        EXPECT_TRUE(same_contact(group[k], one[k])) << lanes << " lanes, sphere " << q << ", contact " << k;
    }
  }
  // What the spheres tested: contacts, and spheres with more triangles in reach than the cap.
  EXPECT_GT(contacts, 100);
  EXPECT_GT(capped, 0);
  std::printf("%d spheres, %d contacts, %d with more than %d triangles in reach\n", queries, contacts, capped,
              kMeshInReachCap);
}

// nearest_over_group: every lane ends with the nearest report of the whole
// list, as one thread finds it, whichever lane held it (spheres under the
// hub's fan, its 64 triangles around the axis within reach of some).
TEST(MeshContactsGroup, LanesAgreeOnTheNearestReport) {
  const MeshSet set = test::single_mesh_set(make_impeller());
  const MeshView m = set.view();
  const double radius = 1.05e-3;
  for (double r : {0.0, 9e-5, 4.6e-4, 1.5e-3})
    for (int a = 0; a < 5; ++a) {
      const Vec3d x(r * std::cos(1.3 * a), r * std::sin(1.3 * a), -1e-3);
      std::vector<std::int32_t> list;
      NearestReport nearest;
      for (std::int32_t t = 0; t < set.n_triangles(); ++t) {
        const ClosestPoint c = triangle_closest_point(m, t, x);
        if (c.distance < 3 * radius) list.push_back(t);
        if (c.distance < radius) nearest.consider(c.distance, c.feature, t);
      }
      const std::int32_t one = nearest.t;
      ASSERT_GE(one, 0);
      for (int lanes : {2, 4, 8, 16, 32}) {
        std::vector<std::int32_t> found(std::size_t(lanes), -2);
        test::run_lanes(lanes, [&](const test::ThreadLane& lane) {
          NearestReport own;  // this lane's share of the list, as the group scan deals it
          for (std::size_t k = std::size_t(lane.rank); k < list.size(); k += std::size_t(lanes)) {
            const ClosestPoint c = triangle_closest_point(m, list[k], x);
            if (c.distance < radius) own.consider(c.distance, c.feature, list[k]);
          }
          nearest_over_group(lane, own);
          found[std::size_t(lane.rank)] = own.t;
        });
        for (int rank = 0; rank < lanes; ++rank)
          EXPECT_EQ(found[std::size_t(rank)], one) << lanes << " lanes, lane " << rank << ", r " << r;
      }
    }
}

}  // namespace
}  // namespace gs
