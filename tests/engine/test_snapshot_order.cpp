// A snapshot holds the owned particles in ascending id order, whatever order
// memory holds them in (the scene's shuffled order, then cell order after a
// re-sort), each row with its own particle's fields, forces, contact count
// and history: checked against the scene itself, free flight and Hooke's law
// for touching pairs. Dense ids and ids far apart (core/id_order.cpp sorts
// the two differently).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "support/support.hpp"

namespace gs {
namespace {

constexpr double kStep = 1e-6, kRadius = 0.001, kStiffness = 1e4, kOverlap = 2e-5;

struct Case {
  SceneSpec scene;
  std::map<ParticleId, ParticleInit> by_id;
  std::map<ParticleId, ParticleId> partner;  // the touching pairs, both ways
};

// 500 free spheres with fields of their own, and 4 pairs pressed kOverlap
// into each other along x, at rest; ids shuffled, `gap` apart.
Case shuffled_case(ParticleId gap) {
  Case c;
  c.scene = test::base_scene(2500, kStiffness, 0.5, 0.5);
  c.scene.effects = kFriction;
  c.scene.gravity = Vec3d();
  c.scene.time_step = kStep;
  const int free = 500, pairs = 4;
  std::vector<ParticleId> ids(free + 2 * pairs);
  std::iota(ids.begin(), ids.end(), ParticleId(0));
  std::shuffle(ids.begin(), ids.end(), std::mt19937(11));
  for (ParticleId& id : ids) id = id * gap + 3;
  for (int k = 0; k < free; ++k) {
    ParticleInit p = test::particle(ids[std::size_t(k)], kRadius * (0.8 + 0.001 * (k % 50)),
                                    Vec3d(-0.015 + 0.003 * (k % 10), -0.015 + 0.003 * (k / 10 % 10), -0.015 + 0.006 * (k / 100)),
                                    Vec3d(0.01 * (k % 7), -0.02 * (k % 5), 0.003 * (k % 11)));
    p.angular_velocity = Vec3d(k % 3, -(k % 4), 0.5 * (k % 2));
    p.marker = std::uint8_t(k % 200);
    c.scene.particles.push_back(p);
  }
  for (int k = 0; k < pairs; ++k) {
    const Vec3d left(-0.015 + 0.008 * k, -0.015, 0.015);
    const ParticleId a = ids[std::size_t(free + 2 * k)], b = ids[std::size_t(free + 2 * k + 1)];
    c.scene.particles.push_back(test::particle(a, kRadius, left));
    c.scene.particles.push_back(test::particle(b, kRadius, left + Vec3d(2 * kRadius - kOverlap, 0, 0)));
    c.partner[a] = b;
    c.partner[b] = a;
  }
  for (const ParticleInit& p : c.scene.particles) c.by_id[p.id] = p;
  return c;
}

// Rows in ascending id order, each with its particle's fields; free particles
// `steps` steps along their flight; the pairs' forces and history at step 0.
void expect_in_id_order(const Case& c, const ParticleSnapshot& s, const HostHistory& h, int steps) {
  ASSERT_EQ(s.size(), c.by_id.size());
  std::size_t r = 0;
  for (const auto& [id, p] : c.by_id) {
    ASSERT_EQ(s.id[r], id) << "row " << r;
    EXPECT_EQ(s.radius[r], float(p.radius)) << id;
    EXPECT_EQ(s.mass[r], float(test::stored_sphere_mass(p.radius, 2500))) << id;
    EXPECT_EQ(s.marker[r], p.marker) << id;
    const bool paired = c.partner.count(id) > 0;
    EXPECT_EQ(s.contacts[r], paired ? 1 : 0) << id;
    ASSERT_EQ(h.slots > 0, true);
    const auto slots = std::size_t(h.slots);
    const std::size_t stored = std::size_t(std::count_if(h.partner.begin() + std::ptrdiff_t(r * slots),
                                                         h.partner.begin() + std::ptrdiff_t((r + 1) * slots),
                                                         [](ParticleId q) { return q != kNoPartner; }));
    EXPECT_EQ(stored, paired ? 1u : 0u) << id;
    if (paired) {
      EXPECT_NE(std::find(h.partner.begin() + std::ptrdiff_t(r * slots), h.partner.begin() + std::ptrdiff_t((r + 1) * slots),
                          c.partner.at(id)),
                h.partner.begin() + std::ptrdiff_t((r + 1) * slots))
          << id;
      if (steps == 0) {  // Hooke: k_n * overlap (of the fp32 radii), pushing the pair apart along x
        const ParticleInit& q = c.by_id.at(c.partner.at(id));
        const double overlap = double(float(p.radius)) + double(float(q.radius)) - std::abs(q.position.x - p.position.x);
        const double sign = q.position.x > p.position.x ? -1 : 1;
        EXPECT_NEAR(s.force[r].x, sign * kStiffness * overlap, 1e-9 * kStiffness * kOverlap) << id;
        EXPECT_EQ(s.force[r].y, 0.0) << id;
      }
      ++r;
      continue;
    }
    Vec3d x = p.position;
    for (int k = 0; k < steps; ++k) x = x + p.velocity * kStep;
    EXPECT_LT(norm(s.position[r] - x), 1e-12) << id;
    EXPECT_EQ(s.velocity[r].x, p.velocity.x) << id;
    EXPECT_EQ(s.angular_velocity[r].y, p.angular_velocity.y) << id;
    EXPECT_EQ(s.force[r].x, 0.0) << id;
    ++r;
  }
}

class SnapshotOrderTest : public testing::TestWithParam<std::tuple<Backend, ParticleId>> {};

TEST_P(SnapshotOrderTest, RowsInIdOrderWithTheirOwnParticlesFields) {
  const Case c = shuffled_case(std::get<1>(GetParam()));
  RunOptions o;
  o.backend = std::get<0>(GetParam());
  o.reorder_interval = 1;  // memory re-sorted by cell at every step
  Simulation sim(c.scene, o);
  ParticleSnapshot s = sim.snapshot();
  HostHistory h = sim.history();
  expect_in_id_order(c, s, h, 0);
  sim.run(3);
  // Again into the arrays of the first snapshot, as output reuses them.
  HostPins pins;
  sim.snapshot_into(s, pins);
  sim.history_into(h, pins);
  EXPECT_EQ(s.step, 3);
  expect_in_id_order(c, s, h, 3);
}

// 64,000 free spheres in flight: on a GPU each field is put in id order a
// chunk of rows at a time (engine/output_chunk.hpp: the positions, 1.5 MB,
// in two chunks of 1 MiB), so that every window of rows, not only the
// first, must hold its own particles.
TEST_P(SnapshotOrderTest, EveryChunkOfALargeBedHoldsItsOwnParticles) {
  const ParticleId gap = std::get<1>(GetParam());
  constexpr int side = 40;
  SceneSpec scene = test::base_scene(2500, kStiffness, 0.5, 0.5);
  scene.gravity = Vec3d();
  scene.time_step = kStep;
  scene.domain_min = {-0.06, -0.06, -0.06};
  scene.domain_max = {0.06, 0.06, 0.06};
  std::vector<ParticleId> ids(side * side * side);
  std::iota(ids.begin(), ids.end(), ParticleId(0));
  std::shuffle(ids.begin(), ids.end(), std::mt19937(3));
  std::map<ParticleId, ParticleInit> by_id;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const int x = int(k) % side, y = int(k) / side % side, z = int(k) / (side * side);
    const ParticleInit p = test::particle(ids[k] * gap + 3, kRadius, Vec3d(-0.05 + 0.0025 * x, -0.05 + 0.0025 * y, -0.05 + 0.0025 * z),
                                          Vec3d(0.01 * (x % 7), -0.02 * (y % 5), 0.003 * (z % 11)));
    scene.particles.push_back(p);
    by_id[p.id] = p;
  }
  RunOptions o;
  o.backend = std::get<0>(GetParam());
  o.reorder_interval = 1;  // memory in cell order, not the scene's
  Simulation sim(scene, o);
  sim.run(1);
  const ParticleSnapshot s = sim.snapshot();
  ASSERT_EQ(s.size(), by_id.size());
  std::size_t r = 0;
  for (const auto& [id, p] : by_id) {
    ASSERT_EQ(s.id[r], id) << "row " << r;
    EXPECT_LT(norm(s.position[r] - (p.position + p.velocity * kStep)), 1e-12) << "row " << r;
    EXPECT_EQ(s.velocity[r].x, p.velocity.x) << "row " << r;
    EXPECT_EQ(s.velocity[r].y, p.velocity.y) << "row " << r;
    ++r;
  }
}

// Ids 1 apart (sorted by scattering them) and 13 apart (by a radix sort).
INSTANTIATE_TEST_SUITE_P(Backends, SnapshotOrderTest,
                         testing::Combine(testing::ValuesIn(test::test_backends()), testing::Values(1u, 13u)),
                         [](const testing::TestParamInfo<std::tuple<Backend, ParticleId>>& info) {
                           return std::string(backend_name(std::get<0>(info.param))) + "_gap" +
                                  std::to_string(std::get<1>(info.param));
                         });

}  // namespace
}  // namespace gs
