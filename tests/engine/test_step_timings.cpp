// The split of a run's time over its phases (Simulation::timings): the
// steps' phases are timed every 128th step and scaled, but a list build is
// rare and costly, and timed every time it runs. Were it left to the timed
// steps, the builds of a run whose timed steps have none would count nothing,
// and their time would be spread over the other phases.
#include <gtest/gtest.h>

#include <random>

#include "support/support.hpp"

namespace gs::test {
namespace {

class StepTimingsTest : public testing::TestWithParam<Backend> {};

// A gas of 20,000 spheres, 1 mm apart, each moving 6 um a step (0.6 m/s):
// the list, whose skin is 40 um, is rebuilt about every second step, not at
// the first (the only timed step of a run this short), and the steps between
// hold few contacts. The builds (a sort and a list of 20,000 spheres each)
// are then most of the run (three quarters on this development machine's
// CPU; 0.3 % when only the timed steps' builds counted).
TEST_P(StepTimingsTest, EveryListBuildCounts) {
  SceneSpec scene = base_scene(2500, 1000, 0.5);
  const double r = 0.0002;
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  ParticleId id = 0;
  for (int i = 0; i < 28; ++i)
    for (int j = 0; j < 28; ++j)
      for (int k = 0; k < 26; ++k) {
        Vec3d v{gauss(rng), gauss(rng), gauss(rng)};
        v = v * (0.6 / norm(v));
        scene.particles.push_back(particle(id++, r, {(i - 13.5) * 1e-3, (j - 13.5) * 1e-3, (k - 12.5) * 1e-3}, v));
      }
  scene.time_step = 1e-5;
  Simulation sim(scene, RunOptions{GetParam()});
  sim.run(120);
  ASSERT_GE(sim.neighbour_builds(), 20) << "the gas should rebuild its list every few steps";
  const StepTimings t = sim.timings();
  const double total = t.integrate + t.neighbours + t.forces + t.exchange;
  ASSERT_GT(total, 0);
  EXPECT_GT(t.neighbours / total, 0.15) << "neighbours " << t.neighbours << " s of " << total << " s, "
                                        << sim.neighbour_builds() << " builds";
}

INSTANTIATE_TEST_SUITE_P(Backends, StepTimingsTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
