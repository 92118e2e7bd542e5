// The orientation quaternion: integrated (q' = 1/2 (0, omega) q, then
// renormalised: integrate/velocity_verlet.hpp) and kept only by a run whose
// snapshots hold it (core/particle_fields.hpp, kOrientations), since nothing
// else reads it. Against the rotation of a freely spinning sphere, exactly
// exp(1/2 omega t); against the same run without it, whose state is otherwise
// the same bit for bit; and a restart from a checkpoint that holds none.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/restart.hpp"
#include "scene/scene_time_step.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

class OrientationTest : public testing::TestWithParam<Backend> {};

constexpr double kRadius = 0.001;

// Spheres far apart (no contacts), spinning at `spins` about their axes.
SceneSpec spinning(const std::vector<Vec3d>& spins) {
  SceneSpec scene = base_scene(2500, 1000, 0.5);
  ParticleId id = 0;
  for (const Vec3d& w : spins) {
    ParticleInit p = particle(id, kRadius, {-0.015 + 0.01 * double(id), 0, 0});
    p.angular_velocity = w;
    scene.particles.push_back(p);
    ++id;
  }
  scene.contact_time = critical_contact_time(scene);
  scene.time_step = 2e-6;
  return scene;
}

// The rotation angle from q to r (unit quaternions; q and -q are one rotation).
double angle_between(const Quaternion& q, const Quaternion& r) {
  const double dot = double(q.w) * r.w + double(q.x) * r.x + double(q.y) * r.y + double(q.z) * r.z;
  return 2.0 * std::acos(std::min(1.0, std::abs(dot)));
}

// A sphere spinning freely at omega from the identity is turned by
// exp(1/2 omega t): the angle |omega| t about omega's axis. Over 20,000 steps
// of 4e-4 rad (8 rad in all) the update's truncation (theta^3 / 12 a step)
// and fp32 rounding stay below 1e-3 rad; an update with a wrong sign, axis
// or factor, or none, is off by radians.
TEST_P(OrientationTest, FollowsTheSpinOfAFreeSphere) {
  const std::vector<Vec3d> spins = {{0, 0, 200}, {200, 0, 0}, Vec3d{3, -4, 12} * (200.0 / 13.0)};
  SceneSpec scene = spinning(spins);
  scene.output.fields = {"orientation"};
  constexpr long long kSteps = 20000;
  Simulation sim(scene, {GetParam()});
  sim.run(kSteps);
  const ParticleSnapshot s = sim.snapshot();
  ASSERT_EQ(s.orientation.size(), spins.size());
  const double t = kSteps * scene.time_step;
  for (std::size_t i = 0; i < spins.size(); ++i) {
    const Vec3d w = spins[std::size_t(s.id[i])];
    const double turn = norm(w) * t, half = 0.5 * turn;
    const Vec3d axis = w * (1.0 / norm(w));
    const Quaternion exact{float(std::cos(half)), float(std::sin(half) * axis.x), float(std::sin(half) * axis.y),
                           float(std::sin(half) * axis.z)};
    EXPECT_LT(angle_between(s.orientation[i], exact), 1e-3) << "sphere " << s.id[i] << " turned by " << turn << " rad";
  }
}

// Two spheres meeting obliquely over a floor, with friction: they spin.
SceneSpec glancing() {
  SceneSpec scene = base_scene(2500, 1000, 0.5, 0.5);
  scene.precision = Precision::fp32;
  scene.effects = kFriction;
  scene.gravity = {0, 0, -9.81};
  scene.walls.push_back(plane_wall({0, 0, -0.01}, {0, 0, 1}));
  scene.particles.push_back(particle(0, kRadius, {-0.003, 0, -0.009}, {0.3, 0, 0}));
  scene.particles.push_back(particle(1, kRadius, {0.003, 0.0012, -0.009}, {-0.3, 0, 0}));
  scene.contact_time = critical_contact_time(scene);
  scene.time_step = 0.02 * scene.contact_time;
  return scene;
}

// Without orientation among its snapshots' fields a run keeps none and the
// rest of its state is what it would be with them, bit for bit.
TEST_P(OrientationTest, KeptOnlyWhereSnapshotsHoldIt) {
  SceneSpec with = glancing(), without = glancing();
  with.output.fields = {"id", "orientation"};
  without.output.fields = {"id", "velocity"};
  Simulation a(with, {GetParam()}), b(without, {GetParam()});
  a.run(3000);
  b.run(3000);
  const ParticleSnapshot sa = a.snapshot(), sb = b.snapshot();
  EXPECT_TRUE(sb.orientation.empty());
  ASSERT_EQ(sa.orientation.size(), 2u);
  EXPECT_GT(angle_between(sa.orientation[0], kNoRotation), 0.01) << "the spheres should spin";
  auto same_bytes = [](const char* name, const auto& x, const auto& y) {
    EXPECT_TRUE(x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0) << name;
  };
  for_each_particle_field(sa, sb, [&](const char* name, const auto& x, const auto& y) {
    if (std::string(name) != "orientation") same_bytes(name, x, y);
  });
  same_bytes("force", sa.force, sb.force);
  same_bytes("torque", sa.torque, sb.torque);
  const HostHistory ha = a.history(), hb = b.history();
  same_bytes("history partner", ha.partner, hb.partner);
  for_each_history_field(ha, hb, [&](const char* name, unsigned, const auto& x, const auto& y) { same_bytes(name, x, y); });
}

// A restart that keeps orientations from a checkpoint of a run that kept
// none starts them unrotated, as for a new particle.
TEST_P(OrientationTest, RestartFromACheckpointWithoutThemStartsThemUnrotated) {
  const SceneSpec without = glancing();
  SceneSpec with = glancing();
  with.output.fields = {"orientation"};
  Simulation first(without, {GetParam()});
  first.run(500);
  const std::string path = testing::TempDir() + "orientation_restart_" + backend_name(GetParam()) + ".h5";
  write_checkpoint(path, make_checkpoint(first.snapshot(), first.history(), first.walls(), 1, 1));
  const Checkpoint back = read_checkpoint(path);
  EXPECT_TRUE(back.particles.orientation.empty());
  Simulation second(with, {GetParam()}, nullptr, restart_state(back));
  const ParticleSnapshot s = second.snapshot();
  ASSERT_EQ(s.orientation.size(), 2u);
  for (const Quaternion& q : s.orientation) EXPECT_EQ(angle_between(q, kNoRotation), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, OrientationTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
