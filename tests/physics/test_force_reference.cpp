// Contact forces of a polydisperse (1:5 diameter ratio) random packing with
// overlaps, as the engine computes them at t = 0, against an independent
// brute-force O(N^2) sum on the host: every pair and every wall, linear
// spring k delta along the normal (zero velocities: no damping; frictionless).
// Agreement to rounding proves that every contact the brute force finds is
// found by the cell-grid search, with the right stiffness for its materials.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kLarge = 0.001, kSmall = 0.0002, kBox = 0.0165;
constexpr int kLargeCount = 400, kSmallCount = 3600;
// Stiffness of the material pairs (0 = large, 1 = small); the walls are material 0.
constexpr double kStiffness[2][2] = {{1000, 2000}, {2000, 3000}};

// Centres uniform in the box, ids in random order of size: deep and shallow
// overlaps of every kind (large-large ~3, large-small ~6 per large sphere),
// and spheres cutting the walls.
SceneSpec packing_scene(Precision precision) {
  SceneSpec scene = base_scene(2500, kStiffness[0][0], 0.5);
  scene.precision = precision;
  scene.materials.push_back(scene.materials[0]);
  scene.materials[1].name = "small";
  for (const auto& [a, b] : {std::pair{0, 1}, std::pair{1, 1}}) {
    PairSpec p = scene.pairs[0];
    p.material_a = a;
    p.material_b = b;
    p.stiffness_normal = kStiffness[a][b];
    scene.pairs.push_back(p);
  }
  scene.domain_min = {-0.001, -0.001, -0.001};
  scene.domain_max = {kBox + 0.001, kBox + 0.001, kBox + 0.001};
  const Vec3d lo(0, 0, 0), hi(kBox, kBox, kBox);
  scene.walls = {plane_wall(lo, {1, 0, 0}), plane_wall(hi, {-1, 0, 0}), plane_wall(lo, {0, 1, 0}),
                 plane_wall(hi, {0, -1, 0}), plane_wall(lo, {0, 0, 1}), plane_wall(hi, {0, 0, -1})};
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> coordinate(0, kBox);
  std::vector<int> material(kLargeCount, 0);
  material.resize(kLargeCount + kSmallCount, 1);
  std::shuffle(material.begin(), material.end(), rng);
  for (std::size_t i = 0; i < material.size(); ++i) {
    const Vec3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    scene.particles.push_back(particle(ParticleId(i), material[i] == 0 ? kLarge : kSmall, x));
    scene.particles.back().material = material[i];
  }
  scene.time_step = 1e-6;
  return scene;
}

struct Reference {
  std::vector<Vec3d> force;
  std::vector<double> magnitude_sum;  // sum of |f| over each sphere's contacts: the rounding scale
  long long particle_contacts = 0, wall_contacts = 0;
};

Reference brute_force(const ParticleSnapshot& s, const std::vector<Wall>& walls) {
  const std::size_t n = s.size();
  Reference ref{std::vector<Vec3d>(n), std::vector<double>(n, 0.0)};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec3d d = s.position[i] - s.position[j];
      const double distance = norm(d);
      const double overlap = double(s.radius[i]) + double(s.radius[j]) - distance;
      if (overlap <= 0) continue;
      const double f = kStiffness[s.material[i]][s.material[j]] * overlap;
      ref.force[i] += d * (f / distance);
      ref.force[j] -= d * (f / distance);
      ref.magnitude_sum[i] += f;
      ref.magnitude_sum[j] += f;
      ++ref.particle_contacts;
    }
    for (const Wall& w : walls) {
      const double overlap = double(s.radius[i]) - dot(s.position[i] - w.point, w.normal);
      if (overlap <= 0) continue;
      const double f = kStiffness[s.material[i]][w.material] * overlap;
      ref.force[i] += w.normal * f;
      ref.magnitude_sum[i] += f;
      ++ref.wall_contacts;
    }
  }
  return ref;
}

class ForceReferenceTest : public testing::TestWithParam<Backend> {};

// fp64: the engine's sum differs from the reference only in rounding and
// summation order, ~1e-16 of the summed magnitudes; bound 1e-12. fp32: the
// overlap, normal and sum are rounded to fp32, ~1e-7; bound 1e-5. A contact
// missed by the search shows as an error of its whole force.
TEST_P(ForceReferenceTest, ForcesMatchBruteForceSum) {
  for (const auto& [precision, tolerance] : {std::pair{Precision::fp64, 1e-12}, std::pair{Precision::fp32, 1e-5}}) {
    SCOPED_TRACE(precision_name(precision));
    const SceneSpec scene = packing_scene(precision);
    const Simulation sim(scene, {GetParam()});  // computes the forces at t = 0
    const ParticleSnapshot s = sim.snapshot();
    ASSERT_EQ(s.size(), std::size_t(kLargeCount + kSmallCount));
    const Reference ref = brute_force(s, scene.walls);
    EXPECT_GT(ref.particle_contacts, 2000);
    EXPECT_GT(ref.wall_contacts, 200);
    int bad = 0, touching = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (ref.magnitude_sum[i] > 0) ++touching;
      const double error = norm(s.force[i] - ref.force[i]);
      if (error > tolerance * ref.magnitude_sum[i] && bad++ < 10)
        ADD_FAILURE() << "particle " << s.id[i] << " (radius " << s.radius[i] << "): force error " << error
                      << " N, reference |f| sum " << ref.magnitude_sum[i] << " N";
    }
    EXPECT_EQ(bad, 0);
    EXPECT_GT(touching, 2000);  // most spheres are in contact
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ForceReferenceTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
