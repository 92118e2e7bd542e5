// Stability case 9 (docs/STABILITY.md): spheres poured onto the seed's
// impeller mesh (3,248 triangles: blade edges and corners, the hub's and the
// shaft's polygon edges, concave corners where blades meet the hub), settled
// with the impeller at rest, then turned at 30 rpm. Contacts at faces, edges
// and vertices, and their hand-over from one feature to the next, must
// neither inject energy nor let a sphere through the surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_time.hpp"
#include "stability/stability_checks.hpp"
#include "walls/impeller.hpp"
#include "walls/sphere_triangle.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0015, kDensity = 2500, kStiffness = 1050, kRestitution = 0.5, kMu = 0.5;
// The box leaves 7.5 mm (2.5 diameters) between the blade tips and its walls:
// the seed's vessel leaves 2.5 mm, less than a diameter, where a sphere is
// squeezed between blade and wall by the geometry alone (measured: 0.3 R).
constexpr double kGravity = 9.81, kHalfWidth = 0.055, kRpm = 30;

// Deepest overlap of any sphere with any triangle of the posed meshes,
// relative to its radius (brute force over all triangles: an independent
// check of the binned search).
double max_mesh_overlap(const ParticleSnapshot& s, const MeshSet& meshes) {
  double worst = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (const MeshCorners& t : meshes.corners) {
      const ClosestPoint c = closest_point_on_triangle(s.position[i], meshes.vertex[t.v[0]], meshes.vertex[t.v[1]],
                                                       meshes.vertex[t.v[2]]);
      worst = std::max(worst, (double(s.radius[i]) - c.distance) / double(s.radius[i]));
    }
  return worst;
}

struct Watch {
  RunRecord run;
  double mesh_overlap = 0;
};

// Samples a run as run_and_watch does, the energy against its value at the
// start of this call, plus the mesh overlap.
Watch watch(Simulation& sim, int samples, long long steps_per_sample, double energy_scale) {
  Watch w;
  const Vec3d gravity = sim.scene().gravity;
  const double e0 = mechanical_energy(sim.snapshot(), gravity);
  for (int k = 0; k < samples && w.run.failures == 0; ++k) {
    const RunRecord r = run_and_watch(sim, 1, steps_per_sample, energy_scale);
    const ParticleSnapshot s = sim.snapshot();
    w.run.failures += r.failures;
    w.run.energy_growth = std::max(w.run.energy_growth, (mechanical_energy(s, gravity) - e0) / energy_scale);
    w.run.overlap.particle = std::max(w.run.overlap.particle, r.overlap.particle);
    w.run.overlap.wall = std::max(w.run.overlap.wall, r.overlap.wall);
    w.run.speed = std::max(w.run.speed, r.speed);
    w.mesh_overlap = std::max(w.mesh_overlap, max_mesh_overlap(s, sim.meshes()));
  }
  return w;
}

class StabilityMeshEdgesTest : public testing::TestWithParam<Backend> {};

// Bounds:
// * settling: mechanical energy never above its initial value by more than
//   1e-3 of the initial potential energy; every overlap (particles, walls, mesh) below the impact bound
//   v sqrt(m / k), v = sqrt(2 g H) from the top of the fill (a sphere against
//   the immovable mesh has the reduced mass m); at rest at the end;
// * turning: a sphere hit by a blade leaves at most at (1 + e)/(1 - e) times
//   the blade tip speed (the fixed point of bouncing between blade and bed),
//   plus the free fall; the mesh overlap stays below 0.25 R (a centre that
//   crossed a 2 mm blade would be within 1 mm of a face: 0.33 R).
TEST_P(StabilityMeshEdgesTest, PouredOntoImpellerThenTurned) {
  const std::size_t count = short_or_long<std::size_t>(600, 7680);
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, kMu);
  // Rolling resistance brings spheres rolling on the floor to rest.
  scene.effects = kFriction | kRollingResistance;
  for (PairSpec& p : scene.pairs) {
    p.rolling_friction = 0.1;
    p.stiffness_rolling = p.stiffness_tangential;
  }
  scene.precision = Precision::fp32;
  scene.gravity = {0, 0, -kGravity};
  const ImpellerSpec spec;
  // The floor 3.5 mm below the hub: spheres on it pass under the blades
  // (no jamming between blade and floor, which the mixer's 2 mm gap allows).
  const double floor = -0.0035, fill_top = spec.hub_height + 2 * kRadius + short_or_long(0.01, 0.16);
  scene.domain_min = {-kHalfWidth - 0.001, -kHalfWidth - 0.001, floor - 0.001};
  scene.domain_max = {kHalfWidth + 0.001, kHalfWidth + 0.001,
                      std::max(spec.hub_height + spec.shaft_length, fill_top) + 0.01};
  scene.walls = box_walls({-kHalfWidth, -kHalfWidth, floor}, {kHalfWidth, kHalfWidth, scene.domain_max.z - 0.001});
  TriangleMesh impeller = make_impeller(spec);
  impeller.name = "impeller";
  MeshMotion turn = rotation_at_rpm({0, 0, 0}, {0, 0, 1}, kRpm);
  const double settle = short_or_long(0.5, 0.8);
  turn.start = settle;
  add_mesh(scene.meshes, impeller, 0, turn);
  // A loose fill around and between the blades and above them, clear of the
  // mesh and outside the hub and the shaft.
  add_random_fill(scene, 0, count * 3, kRadius, kRadius, {-0.045, -0.045, floor + kRadius}, {0.045, 0.045, fill_top},
                  41);
  auto clear_of_impeller = [&](const ParticleInit& p) {
    const double rho2 = p.position.x * p.position.x + p.position.y * p.position.y;
    const double hub = spec.hub_diameter / 2 + kRadius, shaft = spec.shaft_diameter / 2 + kRadius;
    if (rho2 < shaft * shaft || (rho2 < hub * hub && p.position.z < spec.hub_height + kRadius)) return false;
    for (const MeshCorners& t : scene.meshes.corners)
      if (closest_point_on_triangle(p.position, scene.meshes.vertex[t.v[0]], scene.meshes.vertex[t.v[1]],
                                    scene.meshes.vertex[t.v[2]]).distance < kRadius)
        return false;
    return true;
  };
  auto& ps = scene.particles;
  ps.erase(std::remove_if(ps.begin(), ps.end(), [&](const ParticleInit& p) { return !clear_of_impeller(p); }),
           ps.end());
  ASSERT_GE(ps.size(), count);
  ps.resize(count);
  set_largest_accepted_step(scene);

  Simulation sim(scene, {GetParam()});
  const double mass = stored_sphere_mass(kRadius, kDensity);
  const double potential = double(count) * mass * kGravity * (fill_top - floor);
  const double impact_speed = std::sqrt(2 * kGravity * (fill_top - floor));
  const double impact_overlap = impact_speed * std::sqrt(mass / kStiffness) / kRadius;

  const int samples = 25;
  const long long settle_steps = std::llround(settle / scene.time_step);
  const Watch settling = watch(sim, samples, settle_steps / samples, potential);
  const double kinetic_at_rest = kinetic_energy(sim.snapshot());

  const double tip_speed = 2 * M_PI * kRpm / 60 * spec.blade_diameter / 2;
  const double speed_bound = (1 + kRestitution) / (1 - kRestitution) * tip_speed + impact_speed;
  const long long turn_steps = std::llround(short_or_long(0.5, 2.0) / scene.time_step);
  const Watch turning = watch(sim, samples, turn_steps / samples, 1.0);

  std::printf("[ measured ] %zu spheres, %lld steps settling, %lld turning: settling: energy growth %.2e of the "
              "potential, overlaps %.4f R (particles), %.4f R (walls), %.4f R (mesh), impact bound %.4f R, "
              "kinetic at rest %.2e of the potential; turning: max speed %.3g m/s (bound %.3g), overlaps "
              "%.4f R (particles), %.4f R (mesh)\n",
              count, settle_steps, turn_steps, settling.run.energy_growth, settling.run.overlap.particle,
              settling.run.overlap.wall, settling.mesh_overlap, impact_overlap, kinetic_at_rest / potential,
              turning.run.speed, speed_bound, turning.run.overlap.particle, turning.mesh_overlap);
  EXPECT_EQ(settling.run.failures, 0);
  EXPECT_LT(settling.run.energy_growth, 1e-3);
  EXPECT_LT(settling.run.overlap.worst(), impact_overlap);
  EXPECT_LT(settling.mesh_overlap, impact_overlap);
  EXPECT_LT(kinetic_at_rest, 1e-3 * potential);
  EXPECT_EQ(turning.run.failures, 0);
  EXPECT_LT(turning.run.speed, speed_bound);
  EXPECT_LT(turning.run.overlap.worst(), 0.25);
  EXPECT_LT(turning.mesh_overlap, 0.25);
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityMeshEdgesTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
