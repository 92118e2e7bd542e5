// Stability case 5 (docs/STABILITY.md): the same bed at the origin and
// shifted 1e3 m and 1e5 m along every axis, in both force precisions.
// Positions are fp64 and relative positions are formed in fp64 before the
// forces narrow them, so a far bed must behave like a near one up to the
// rounding of its absolute positions: ulp(1e5 m) = 1.5e-11 m.
//
// The bed is a simple cubic lattice with horizontal gaps dropped onto the
// floor: each column is a chain of spheres whose contacts stay aligned
// (identical x and y), so no rounding difference is amplified by chaotic
// granular dynamics and the comparison can be particle by particle.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_time.hpp"
#include "scene/position_resolution.hpp"
#include "stability/stability_checks.hpp"

namespace gs::test {
namespace {

constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kRestitution = 0.5, kGravity = 9.81;

SceneSpec lattice_bed(double shift, Precision precision, int per_side, int layers) {
  SceneSpec scene = base_scene(kDensity, kStiffness, kRestitution, 0.5);
  scene.effects = kFriction;
  scene.precision = precision;
  scene.gravity = {0, 0, -kGravity};
  const Vec3d offset(shift, shift, shift);
  const double width = per_side * 2.2 * kRadius, height = (layers + 1) * 2.1 * kRadius;
  scene.domain_min = offset + Vec3d(-0.001, -0.001, -0.001);
  scene.domain_max = offset + Vec3d(width + 0.001, width + 0.001, height + 0.001);
  scene.walls = box_walls(offset, offset + Vec3d(width, width, height));
  ParticleId id = 0;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < per_side; ++j)
      for (int i = 0; i < per_side; ++i) {
        const Vec3d local((i + 0.5) * 2.2 * kRadius, (j + 0.5) * 2.2 * kRadius, (k + 0.5) * 2.1 * kRadius);
        scene.particles.push_back(particle(id++, kRadius, offset + local));
      }
  set_largest_accepted_step(scene);
  return scene;
}

// Last ulp of a double of magnitude x.
double ulp(double x) { return std::nextafter(x, 2 * x + 1) - x; }

class StabilityFarFromOriginTest : public testing::TestWithParam<Backend> {};

// Bound, for every sphere: |(x_far - shift) - x_near| <= N ulp(X) with N the
// steps run and X the largest coordinate, plus N ulp_fp32(2 R) in fp32.
// Each drift x += v dt rounds the far position to half an ulp(X), once per
// step, and the bed (dissipative, every contact stays a spring along the
// same axis) does not amplify the differences: at most N ulp(X) / 2 per
// coordinate, doubled for margin. In fp32 the narrowed relative positions
// can round apart by one fp32 ulp of a separation (2.3e-10 m for 2 R) when
// the fp64 values straddle a rounding boundary, a force error of k ulp; the
// same count bounds its accumulation. 1e5 m, 2000 steps: 2.9e-8 m = 3e-5 R
// (fp64) and 4.7e-7 m (fp32); measured 3e-11 m (two ulps) in both: the
// springs pull the settled bed back to the same balance. Velocities: the
// position bound times 2 omega0 (a spring displaced by it oscillates at
// omega0). Energy (from the floor) never above E0 by 1e-3 of it; overlaps
// below 1% of R (the bed's static load, 6 layers m g / k, is 0.06%, the fall
// of 0.1 R gaps adds a few times that).
TEST_P(StabilityFarFromOriginTest, FarBedMatchesBedAtOrigin) {
  const int per_side = short_or_long(4, 30), layers = short_or_long(6, 20);
  const long long steps = short_or_long(2000LL, 20000LL);
  for (const Precision precision : {Precision::fp64, Precision::fp32}) {
    const SceneSpec near_scene = lattice_bed(0, precision, per_side, layers);
    Simulation near_sim(near_scene, {GetParam()});
    near_sim.run(steps);
    const ParticleSnapshot near = near_sim.snapshot();
    ASSERT_EQ(expect_healthy(near, near_scene, near_sim.walls()), 0);
    for (const double shift : {1e3, 1e5}) {
      SCOPED_TRACE(std::string(precision_name(precision)) + ", shift " + std::to_string(shift));
      const SceneSpec far_scene = lattice_bed(shift, precision, per_side, layers);
      Simulation far_sim(far_scene, {GetParam()});
      const Vec3d floor(shift, shift, shift);
      const double e0 = mechanical_energy(far_sim.snapshot(), far_scene.gravity, floor);
      const RunRecord r = run_and_watch(far_sim, 10, steps / 10, e0, floor);
      ASSERT_EQ(r.failures, 0);
      const ParticleSnapshot far = far_sim.snapshot();
      double position_error = 0, velocity_error = 0;
      for (std::size_t i = 0; i < far.size(); ++i) {
        position_error = std::max(position_error, norm(far.position[i] - floor - near.position[i]));
        velocity_error = std::max(velocity_error, norm(far.velocity[i] - near.velocity[i]));
      }
      double bound = double(steps) * ulp(far_scene.domain_max.x);
      const float separation = float(2 * kRadius);
      if (precision == Precision::fp32) bound += double(steps) * double(std::nextafter(separation, 1.0f) - separation);
      const double velocity_bound = 2 * bound * std::sqrt(2 * kStiffness / stored_sphere_mass(kRadius, kDensity));
      std::printf("[ measured ] %s, shift %.0e m, %lld steps: position difference %.3g m (bound %.3g m), velocity "
                  "difference %.3g m/s (bound %.3g m/s), energy growth %.3g E0, max overlap %.4f R\n",
                  precision_name(precision), shift, steps, position_error, bound,
                  velocity_error, velocity_bound, r.energy_growth, r.overlap.worst());
      EXPECT_LT(position_error, bound);
      EXPECT_LT(velocity_error, velocity_bound);
      EXPECT_LT(r.energy_growth, 1e-3);
      EXPECT_LT(r.overlap.worst(), 0.01);
    }
  }
}

// Precision fp32_full (state kept in fp32, as the seed): the bed at the
// origin stays healthy, its state stays on the fp32 grid, and it follows the
// fp32-forces run within N fp32 spacings of its largest coordinate (each
// drift rounds once, by the same argument as above); 2000 steps at 0.015 m:
// 1.9e-6 m, measured 5e-10 m on the CPU. At 1e3 m and 1e5 m the fp32
// spacings (6.1e-5 m, 7.8e-3 m) exceed a thousandth of the radius, so the run
// is refused before it starts.
TEST_P(StabilityFarFromOriginTest, Fp32StateHealthyAtOriginRefusedFarFromIt) {
  const int per_side = short_or_long(4, 30), layers = short_or_long(6, 20);
  const long long steps = short_or_long(2000LL, 20000LL);
  const SceneSpec fp32_scene = lattice_bed(0, Precision::fp32, per_side, layers);
  const SceneSpec full_scene = lattice_bed(0, Precision::fp32_full, per_side, layers);
  Simulation fp32_sim(fp32_scene, {GetParam()}), full_sim(full_scene, {GetParam()});
  fp32_sim.run(steps);
  const double e0 = mechanical_energy(full_sim.snapshot(), full_scene.gravity, Vec3d());
  const RunRecord r = run_and_watch(full_sim, 10, steps / 10, e0, Vec3d());
  ASSERT_EQ(r.failures, 0);
  const ParticleSnapshot fp32 = fp32_sim.snapshot(), full = full_sim.snapshot();
  ASSERT_EQ(expect_healthy(full, full_scene, full_sim.walls()), 0);
  auto on_grid = [](const Vec3d& v) {
    return double(float(v.x)) == v.x && double(float(v.y)) == v.y && double(float(v.z)) == v.z;
  };
  double difference = 0;
  for (std::size_t i = 0; i < full.size(); ++i) {
    ASSERT_TRUE(on_grid(full.position[i]) && on_grid(full.velocity[i])) << "particle " << full.id[i];
    difference = std::max(difference, norm(full.position[i] - fp32.position[i]));
  }
  const double bound = double(steps) * fp32_spacing(full_scene.domain_max.z);
  std::printf("[ measured ] fp32_full at the origin, %lld steps: %.3g m from the fp32-forces run (bound %.3g m), "
              "energy growth %.3g E0, max overlap %.4f R\n", steps, difference, bound, r.energy_growth,
              r.overlap.worst());
  EXPECT_LT(difference, bound);
  EXPECT_LT(r.energy_growth, 1e-3);
  EXPECT_LT(r.overlap.worst(), 0.01);
  for (const double shift : {1e3, 1e5}) {
    try {
      Simulation far(lattice_bed(shift, Precision::fp32_full, per_side, layers), {GetParam()});
      ADD_FAILURE() << "fp32_full at " << shift << " m was not refused";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("precision fp32_full"), std::string::npos) << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, StabilityFarFromOriginTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
