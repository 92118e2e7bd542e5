// Insertion into a box periodic in x and y (engine/insertion.hpp): an inlet
// over the whole cross-section must not place a particle onto the periodic
// image of one that straddles a face. Overlaps are measured to the nearest
// image, directly over every pair.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/periodic_box.hpp"
#include "engine/insertion.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kLength = 0.008;  // the box along x and y [m]

// Deepest overlap over every pair, to the nearest image, relative to the sum of radii (<= 0: none).
double deepest_periodic_overlap(const ParticleSnapshot& s, const PeriodicBox& box) {
  double worst = -1;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const double sum = double(s.radius[i]) + double(s.radius[j]);
      worst = std::max(worst, (sum - norm(box.separation(s.position[i], s.position[j]))) / sum);
    }
  return worst;
}

// Spheres of 1 mm radius straddling the x and y faces (centres 0.3 mm inside
// the max faces, so each reaches 0.7 mm into the box through the min faces),
// no gravity, nothing moving; an inlet over the whole cross-section in the
// same z range, feeding 0.5 mm spheres densely.
SceneSpec periodic_box_with_inlet() {
  SceneSpec s = base_scene(2500, 2000, 0.5, 0.5);
  s.domain_min = {0, 0, 0};
  s.domain_max = {kLength, kLength, 0.006};
  s.periodic_axes = 3;
  s.walls = {plane_wall({0, 0, 0}, {0, 0, 1})};
  const double edge = kLength - 0.0003;
  ParticleId id = 0;
  for (double at : {0.001, 0.004, 0.0065}) s.particles.push_back(particle(id++, 0.001, {edge, at, 0.0025}));
  for (double at : {0.0025, 0.0055}) s.particles.push_back(particle(id++, 0.001, {at, edge, 0.0025}));
  InletSpec in;
  in.name = "feed";
  in.region.min = {0, 0, 0.001};
  in.region.max = {kLength, kLength, 0.004};
  in.size.kind = SizeSpec::Kind::uniform;
  in.size.radius_min = 0.0005;
  in.size.radius_max = 0.0005;
  in.rate = 0;
  in.total = 80;  // all due at the first batch: they compete for room
  in.attempts = 200;
  in.interval_steps = 5;
  in.seed = 5;
  s.inlets.push_back(in);
  s.time_step = 1e-6;
  return s;
}

class PeriodicInsertion : public ::testing::TestWithParam<Backend> {};

TEST_P(PeriodicInsertion, NoOverlapAcrossThePeriodicFaces) {
  const SceneSpec s = periodic_box_with_inlet();
  RunOptions o;
  o.backend = GetParam();
  Simulation sim(s, o);
  const PeriodicBox box = make_periodic_box(s.periodic_axes, s.domain_min, s.domain_max);
  for (int batch = 1; batch <= 6; ++batch) {
    sim.run(5);
    const ParticleSnapshot snap = sim.snapshot();
    EXPECT_LE(deepest_periodic_overlap(snap, box), 1e-9) << "after batch " << batch;
  }
  // The test needs the inlet to have placed particles near the faces.
  const ParticleSnapshot snap = sim.snapshot();
  std::size_t near_min_face = 0;
  for (std::size_t i = 0; i < snap.size(); ++i)
    if (snap.radius[i] < 0.0008f && (snap.position[i].x < 0.0015 || snap.position[i].y < 0.0015)) ++near_min_face;
  EXPECT_GT(snap.size(), s.particles.size() + 40);
  EXPECT_GT(near_min_face, 10u);
}

INSTANTIATE_TEST_SUITE_P(Backends, PeriodicInsertion, ::testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
