// The meshes' near lists (walls/mesh_near.hpp): a list holds every triangle
// within the sphere's radius plus the skin, from the run's bins; the bound on
// a mesh's motion bounds every vertex's; and a mesh that moves onto spheres
// at rest, which never move half the skin themselves, meets them as in a run
// that builds every list at every step, bit for bit, on every backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "contact/contact_time.hpp"
#include "mesh_test_helpers.hpp"
#include "support/support.hpp"
#include "walls/impeller.hpp"
#include "walls/mesh_drift.hpp"
#include "walls/mesh_near.hpp"

namespace gs::test {
namespace {

// Every triangle within near_reach of the sphere, ascending, by a scan of all.
std::vector<std::int32_t> near_by_scan(const MeshView& view, std::int32_t n_triangles, const Vec3d& x, double radius,
                                       double skin) {
  std::vector<std::int32_t> out;
  for (std::int32_t t = 0; t < n_triangles; ++t)
    if (triangle_closest_point(view, t, x).distance <= near_reach(radius, skin)) out.push_back(t);
  return out;
}

// The impeller turned and shifted, spheres of radii up to the largest
// scattered over and around it: each near list, built from the run's bins
// by the two passes, is the scan's.
TEST(MeshNearList, HoldsEveryTriangleWithinTheRadiusAndTheSkin) {
  MeshSet set;
  add_mesh(set, make_impeller(), 0, rotation_at_rpm(Vec3d(0.001, 0, 0), Vec3d(0.1, 0, 1), 30, Vec3d(0, 0.01, 0)));
  add_mesh(set, make_impeller(), 0, rotation_at_rpm(Vec3d(), Vec3d(0, 0, 1), -20));
  set_mesh_poses(set, 0.37);
  move_meshes(set, 0.37);
  const double largest = 0.0015, skin = 0.3 * 2 * largest, cell = 2 * largest + skin;
  const MeshBins bins = bin_triangles(set, cell, run_binning(cell, skin));
  const MeshView view = with_bins(set.view(), bins);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> across(-0.055, 0.055), up(-0.01, 0.03), size(0.3 * largest, largest);
  std::vector<Vec3d> x;
  std::vector<float> radius;
  for (int k = 0; k < 4000; ++k) {
    x.emplace_back(across(rng), across(rng), up(rng));
    radius.push_back(float(size(rng)));
  }
  const Index n = Index(x.size());
  std::vector<ListOffset> begin(x.size() + 1);
  const MeshNearPass<false> count{view, x.data(), radius.data(), skin, begin.data(), nullptr};
  for (Index i = 0; i < n; ++i) count(i);
  for (Index i = 0; i < n; ++i) begin[i + 1] += begin[i];
  std::vector<std::int32_t> triangles(begin.back());
  const MeshNearPass<true> fill{view, x.data(), radius.data(), skin, begin.data(), triangles.data()};
  for (Index i = 0; i < n; ++i) fill(i);
  std::size_t listed = 0;
  for (Index i = 0; i < n; ++i) {
    const std::vector<std::int32_t> got(triangles.begin() + begin[i], triangles.begin() + begin[i + 1]);
    ASSERT_EQ(got, near_by_scan(view, set.n_triangles(), x[i], radius[i], skin)) << "sphere " << i;
    listed += got.size();
  }
  EXPECT_GT(listed, 1000u) << "too few spheres near the impellers to test anything";
}

// Random rigid motions of the impeller: no vertex moves further than the
// bound, and for a pure turn the bound is within a factor 2.5 of the
// furthest vertex's move (the centre of the bounds lies off the axis).
TEST(MeshNearList, DisplacementBoundHoldsEveryVertex) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 200; ++k) {
    MeshSet set;
    const Vec3d axis(u(rng), u(rng), u(rng)), point(0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng));
    const bool turn_only = k % 2 == 0;
    const Vec3d velocity = turn_only ? Vec3d() : Vec3d(u(rng), u(rng), u(rng)) * 0.05;
    add_mesh(set, make_impeller(), 0, rotation_at_rpm(point, axis, 60 * u(rng), velocity));
    const double t0 = std::abs(u(rng)), t1 = t0 + 0.05 * std::abs(u(rng));
    MeshDrift drift(set);
    move_meshes(set, t0);
    const std::vector<Vec3d> before = set.vertex;
    drift.built(set);
    move_meshes(set, t1);
    double moved = 0;
    for (std::size_t v = 0; v < before.size(); ++v) moved = std::max(moved, norm(set.vertex[v] - before[v]));
    EXPECT_TRUE(drift.beyond(set, moved * (1 - 1e-9))) << "motion " << k << ": a vertex moved " << moved;
    if (turn_only) {
      EXPECT_FALSE(drift.beyond(set, 2.5 * moved)) << "motion " << k << ": a vertex moved " << moved;
    }
  }
}

// R = 2^-10 m, exact in fp32.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5;

class MeshNearRunTest : public testing::TestWithParam<Backend> {};

// Three spheres at rest, no gravity, further than the radius and the skin
// from a mesh that then moves onto them: a plate rising along its normal,
// and a paddle turning about an axis. Nothing moves the spheres before the
// mesh strikes them, so only the mesh's drift can call for the lists the
// strike needs; with a skin of 0.5 diameters the run must give the bits of
// the run that builds its lists every step (no skin).
TEST_P(MeshNearRunTest, AMovingMeshStrikesSpheresAtRestAsWithoutASkin) {
  const double h = 0.001;  // the meshes' cells
  const struct {
    const char* what;
    FlatSquare mesh;
    MeshMotion motion;
    std::vector<Vec3d> at;
  } cases[] = {
      {"plate rising at 0.1 m/s", make_flat_square(8, h, 0.2, Rotation(Vec3d(0, 0, 1), 0), Vec3d(-0.004, -0.004, 0), 3),
       rotation_at_rpm(Vec3d(), Vec3d(0, 0, 1), 0, Vec3d(0, 0, 0.1)),
       {{0, 0, 0.004}, {0.0021, 0, 0.0042}, {-0.001, 0.0025, 0.0045}}},
      {"paddle turning at 120 rpm",
       make_flat_square(8, h, 0.2, Rotation(Vec3d(1, 0, 0), M_PI / 2), Vec3d(0.0005, 0, -0.004), 4),
       rotation_at_rpm(Vec3d(), Vec3d(0, 0, 1), 120),
       {{0.005 * std::cos(0.7), 0.005 * std::sin(0.7), 0}, {0.0075 * std::cos(0.9), 0.0075 * std::sin(0.9), 0.001},
        {0.003 * std::cos(1.1), 0.003 * std::sin(1.1), -0.001}}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
    scene.effects = kFriction;
    scene.gravity = {0, 0, 0};
    const double mass = stored_sphere_mass(kRadius, kDensity);
    scene.time_step = linear_contact_time(kStiffness, mass, kRestitution) / 30;
    scene.domain_min = {-0.012, -0.012, -0.006};
    scene.domain_max = {0.012, 0.012, 0.015};
    add_mesh(scene.meshes, c.mesh.mesh, 0, c.motion);
    for (std::size_t k = 0; k < c.at.size(); ++k) scene.particles.push_back(particle(ParticleId(k), kRadius, c.at[k]));
    SceneSpec every_step = scene;
    scene.verlet_skin = 0.5;
    every_step.verlet_skin = 0;
    Simulation with_skin(scene, {GetParam()}), without(every_step, {GetParam()});
    const long long steps = std::llround(0.06 / scene.time_step);
    with_skin.run(steps);
    without.run(steps);
    const ParticleSnapshot a = with_skin.snapshot(), b = without.snapshot();
    EXPECT_TRUE(same_bits(a.position, b.position));
    EXPECT_TRUE(same_bits(a.velocity, b.velocity));
    EXPECT_TRUE(same_bits(a.angular_velocity, b.angular_velocity));
    double fastest = 0;
    for (const Vec3d& v : b.velocity) fastest = std::max(fastest, norm(v));
    EXPECT_GT(fastest, 0.02) << "the mesh should have struck the spheres";
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, MeshNearRunTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
