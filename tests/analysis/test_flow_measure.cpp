// Flow through a surface (analysis/flow_measure.hpp): particles in free fall
// cross a plane in the sampling interval that holds their analytic crossing
// time sqrt(2 h / g); a column moving at a known speed gives the exact mass
// flow m v / d; bounds (disk, rectangle), signs and the documented limit (a
// particle through and back between two samples is not counted).
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/flow_measure.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kGravity = 9.81, kRadius = 0.001, kPlaneZ = 0.5, kSample = 0.01, kDt = 1e-4;

// Two materials (the second three times as dense), no contacts: the
// particles stand 1 cm apart and fall side by side.
SceneSpec open_scene() {
  SceneSpec scene = base_scene(2500, 1000, 0.5);
  scene.domain_min = {-0.01, -0.01, 0};
  scene.domain_max = {0.2, 0.2, 1};
  MaterialSpec heavy = scene.materials[0];
  heavy.name = "heavy";
  heavy.density = 7500;
  scene.materials.push_back(heavy);
  PairSpec p = scene.pairs[0];
  for (int b : {0, 1}) {
    p.material_a = b == 0 ? 0 : 1;
    p.material_b = 1;
    scene.pairs.push_back(p);
  }
  scene.time_step = kDt;
  return scene;
}

FlowSpec plane_down() {
  FlowSpec f;
  f.name = "plane";
  f.point = {0.05, 0.05, kPlaneZ};
  f.normal = {0, 0, -1};  // downward crossings count +1
  f.markers = {1};
  return f;
}

// Runs `scene` and counts the flow every kSample seconds; per interval j
// (ending at j kSample) the tally of every group.
std::vector<std::vector<FlowGroup>> sampled_flow(const SceneSpec& scene, const FlowSpec& f, int intervals,
                                                 Backend backend) {
  Simulation sim(scene, {backend});
  FlowCounter counter(f, {"m", "heavy"});
  std::vector<std::vector<FlowGroup>> out;
  counter.update(sim.snapshot());
  for (int j = 1; j <= intervals; ++j) {
    sim.run(std::llround(kSample / kDt));
    counter.update(sim.snapshot());
    out.push_back(counter.groups());
  }
  return out;
}

class FlowTest : public testing::TestWithParam<Backend> {};

// Ten spheres dropped from rest at heights h_k above the plane whose crossing
// times t_k = sqrt(2 h_k / g) = 15, 25, ..., 105 ms lie mid-interval (velocity
// Verlet is exact under a constant force); a sphere thrown up through the
// plane from 2 mm below at 0.6 m/s crosses it upwards at t_1 = (v - sqrt(v^2 -
// 2 g d)) / g = 3.4 ms and down again at t_2 = 118.9 ms; one thrown at
// 0.03 m/s from 20 um below crosses up and down within the first interval,
// which the sampled positions cannot see.
TEST_P(FlowTest, FreeFallCrossesInTheIntervalOfTheAnalyticTime) {
  SceneSpec scene = open_scene();
  scene.gravity = {0, 0, -kGravity};
  std::vector<double> time;  // analytic crossing time of each dropped sphere
  for (int k = 0; k < 10; ++k) {
    time.push_back(0.015 + 0.01 * k);
    ParticleInit p = particle(ParticleId(k), kRadius, {0.01 * k, 0.02, kPlaneZ + 0.5 * kGravity * time[k] * time[k]});
    p.material = k % 2;
    scene.particles.push_back(p);
  }
  const double v = 0.6, d = 0.002, root = std::sqrt(v * v - 2 * kGravity * d);
  const double up = (v - root) / kGravity, down = (v + root) / kGravity;
  ParticleInit thrown = particle(10, kRadius, {0.1, 0.1, kPlaneZ - d}, {0, 0, v});
  thrown.marker = 1;
  scene.particles.push_back(thrown);
  scene.particles.push_back(particle(11, kRadius, {0.15, 0.1, kPlaneZ - 2e-5}, {0, 0, 0.03}));

  const std::vector<std::vector<FlowGroup>> flow = sampled_flow(scene, plane_down(), 13, GetParam());
  const double m0 = stored_sphere_mass(kRadius, 2500), m1 = stored_sphere_mass(kRadius, 7500);
  for (int j = 1; j <= 13; ++j) {
    SCOPED_TRACE("interval ending at " + std::to_string(j * kSample) + " s");
    long long down_expected = 0, up_expected = 0;
    double mass_expected[2] = {0, 0};
    for (int k = 0; k < 10; ++k)
      if (std::ceil(time[k] / kSample) == j) {
        ++down_expected;
        mass_expected[k % 2] += k % 2 ? m1 : m0;
      }
    if (std::ceil(up / kSample) == j) ++up_expected;
    if (std::ceil(down / kSample) == j) {
      ++down_expected;
      mass_expected[0] += m0;
    }
    const FlowTally& all = flow[std::size_t(j - 1)][0].interval;
    EXPECT_EQ(all.forward, down_expected);
    EXPECT_EQ(all.backward, up_expected);
    EXPECT_EQ(flow[std::size_t(j - 1)][1].interval.forward_mass, mass_expected[0]);
    EXPECT_EQ(flow[std::size_t(j - 1)][2].interval.forward_mass, mass_expected[1]);
    // Marker 1: only the thrown sphere.
    EXPECT_EQ(flow[std::size_t(j - 1)][3].interval.net_count(), -long(j == 1) + long(j == 12));
  }
  const FlowTally& total = flow.back()[0].cumulative;
  EXPECT_EQ(total.forward, 11);
  EXPECT_EQ(total.backward, 1);
  EXPECT_DOUBLE_EQ(total.net_mass(), 5 * m0 + 5 * m1);
}

// A column of spheres d = 5 mm apart moving down at v = 1 m/s through the
// plane: m v / d of mass per second, 2 spheres in each 10 ms.
TEST_P(FlowTest, SteadyColumnGivesTheExactMassFlow) {
  SceneSpec scene = open_scene();
  const double v = 1.0, spacing = 0.005;
  for (int i = 0; i < 40; ++i)
    scene.particles.push_back(particle(ParticleId(i), kRadius, {0.05, 0.05, kPlaneZ + 0.0025 + spacing * i}, {0, 0, -v}));
  FlowSpec disk = plane_down();
  disk.bound = FlowBound::disk;
  disk.radius = 0.001;
  const std::vector<std::vector<FlowGroup>> flow = sampled_flow(scene, disk, 8, GetParam());
  const double m = stored_sphere_mass(kRadius, 2500);
  for (const std::vector<FlowGroup>& g : flow) {
    EXPECT_EQ(g[0].interval.forward, 2);
    EXPECT_EQ(g[0].interval.backward, 0);
  }
  FlowCounter counter(disk, {"m", "heavy"});
  ParticleSnapshot a, b;
  a.id = b.id = {0};
  a.mass = b.mass = {float(m)};
  a.material = b.material = {0};
  a.marker = b.marker = {0};
  a.position = {{0.05, 0.05, kPlaneZ + 0.001}};
  b.position = {{0.05, 0.05, kPlaneZ - 0.001}};
  b.time = kSample;
  counter.update(a);
  counter.update(b);
  EXPECT_DOUBLE_EQ(counter.groups()[0].interval.net_mass() / counter.interval_seconds(), m / kSample);
  EXPECT_EQ(flow.back()[0].cumulative.forward, 16);
  EXPECT_NEAR(flow.back()[0].cumulative.net_mass() / (8 * kSample), m * v / spacing, 1e-12 * m * v / spacing);
}

INSTANTIATE_TEST_SUITE_P(Backends, FlowTest, testing::ValuesIn(test_backends()), backend_label);

// Signs and bounds of one crossing, from the straight segment between samples.
TEST(FlowCrossing, SignAndBounds) {
  FlowSpec f = plane_down();
  const Vec3d above{0.05, 0.05, kPlaneZ + 0.01}, below{0.05, 0.05, kPlaneZ - 0.01};
  EXPECT_EQ(flow_crossing(f, above, below), 1);
  EXPECT_EQ(flow_crossing(f, below, above), -1);
  EXPECT_EQ(flow_crossing(f, above, above), 0);
  // A centre on the plane is on the front side (n . (x - p) >= 0), here below it.
  const Vec3d on{0.05, 0.05, kPlaneZ};
  EXPECT_EQ(flow_crossing(f, on, below), 0);
  EXPECT_EQ(flow_crossing(f, above, on), 1);
  EXPECT_EQ(flow_crossing(f, on, above), -1);
  f.bound = FlowBound::disk;
  f.radius = 0.01;
  const Vec3d shift{0.009, 0.004, 0};  // |shift| = 0.00985 < 0.01
  EXPECT_EQ(flow_crossing(f, above + shift, below + shift), 1);
  // Through the disk's rim at a slant: the crossing point decides, not the ends.
  EXPECT_EQ(flow_crossing(f, above + Vec3d(0.012, 0, 0), below - Vec3d(0.012, 0, 0)), 1);
  EXPECT_EQ(flow_crossing(f, above + Vec3d(0.011, 0, 0), below + Vec3d(0.011, 0, 0)), 0);
  f.bound = FlowBound::rectangle;
  f.axis_u = {1, 0, 0};
  f.axis_v = cross(f.normal, f.axis_u);
  f.half_length_u = 0.02;
  f.half_length_v = 0.005;
  EXPECT_EQ(flow_crossing(f, above + Vec3d(0.019, 0.004, 0), below + Vec3d(0.019, 0.004, 0)), 1);
  EXPECT_EQ(flow_crossing(f, above + Vec3d(0.019, 0.006, 0), below + Vec3d(0.019, 0.006, 0)), 0);
  EXPECT_EQ(flow_crossing(f, above + Vec3d(0.021, 0, 0), below + Vec3d(0.021, 0, 0)), 0);
}

// The log's cumulative columns give back the totals bit for bit (a restart
// continues from them).
TEST(FlowLog, CumulativeTotalsRoundTrip) {
  FlowCounter counter(plane_down(), {"m", "heavy"});
  ParticleSnapshot a, b;
  a.id = b.id = {3, 7};
  a.mass = b.mass = {0.1f / 3, 0.7f};
  a.material = b.material = {0, 1};
  a.marker = b.marker = {1, 0};
  a.position = {{0, 0, kPlaneZ + 0.1}, {0, 0, kPlaneZ - 0.1}};
  b.position = {{0, 0, kPlaneZ - 0.1}, {0, 0, kPlaneZ + 0.1}};
  b.time = 0.3;
  counter.update(a);
  counter.update(b);
  std::vector<std::vector<std::string>> rows;
  for (const std::string& line : flow_csv_rows(counter, 0.3, 30)) {
    std::vector<std::string> fields;
    std::size_t at = 0;
    for (std::size_t comma; (comma = line.find(',', at)) != std::string::npos; at = comma + 1)
      fields.push_back(line.substr(at, comma - at));
    fields.push_back(line.substr(at));
    rows.push_back(fields);
  }
  const std::vector<FlowTally> back = flow_cumulative_from_rows(counter, rows);
  ASSERT_EQ(back.size(), counter.groups().size());
  for (std::size_t g = 0; g < back.size(); ++g) {
    EXPECT_EQ(back[g].forward, counter.groups()[g].cumulative.forward);
    EXPECT_EQ(back[g].backward, counter.groups()[g].cumulative.backward);
    EXPECT_EQ(back[g].forward_mass, counter.groups()[g].cumulative.forward_mass);
    EXPECT_EQ(back[g].backward_mass, counter.groups()[g].cumulative.backward_mass);
  }
  EXPECT_EQ(back[0].forward, 1);
  EXPECT_EQ(back[0].backward, 1);
  EXPECT_EQ(back[3].forward, 1);  // marker 1: particle 3, downwards
}

}  // namespace
}  // namespace gs::test
