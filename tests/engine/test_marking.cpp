// Marking by side of a plane (the seed's procedure after settling): every
// owned particle gets the front marker where (x - p) . n >= 0, the back one
// elsewhere, on every backend; the markers then travel with the particles.
#include <gtest/gtest.h>

#include "support/support.hpp"

namespace gs {
namespace {

class MarkingTest : public testing::TestWithParam<Backend> {};

TEST_P(MarkingTest, SidesOfAnInclinedPlane) {
  SceneSpec s = test::base_scene(2500, 1e4, 0.5);
  s.domain_min = Vec3d(-1, -1, -1);
  s.domain_max = Vec3d(1, 1, 1);
  s.gravity = Vec3d();
  const Vec3d point(0.1, 0, 0), normal = Vec3d(1, 1, 0) * (1 / std::sqrt(2.0));
  ParticleId id = 0;
  for (double x = -0.8; x <= 0.8; x += 0.1)
    for (double y = -0.8; y <= 0.8; y += 0.1) s.particles.push_back(test::particle(id++, 0.01, Vec3d(x, y, 0)));
  s.particles.push_back(test::particle(id++, 0.01, point));  // on the plane: front
  s.time_step = 1e-4;
  RunOptions o;
  o.backend = GetParam();
  Simulation sim(s, o);
  sim.mark(MarkingSpec{0, point, normal, 7, 3});
  sim.run(2);
  const ParticleSnapshot snap = sim.snapshot();
  ASSERT_EQ(snap.id.size(), s.particles.size());
  int front = 0;
  for (std::size_t i = 0; i < snap.id.size(); ++i) {
    const Vec3d x = s.particles[snap.id[i]].position;
    const bool ahead = dot(x - point, normal) >= 0;
    EXPECT_EQ(snap.marker[i], ahead ? 7 : 3) << "particle " << snap.id[i];
    front += ahead;
  }
  EXPECT_GT(front, 10);
  EXPECT_LT(front, int(snap.id.size()) - 10);
}

INSTANTIATE_TEST_SUITE_P(Backends, MarkingTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
