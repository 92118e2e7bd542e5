// A run's snapshots and checkpoints are written from one set of host arrays
// that the next output refills (run/run_output.hpp): a refill must wait until
// the writer's thread has finished the file it reads. Back-to-back outputs of
// two simulations with different particles, each file against the
// particles it must hold, computed here from the scene (free flight).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numeric>
#include <random>

#include "comm/transport.hpp"
#include "core/wall_clock.hpp"
#include "io/checkpoint.hpp"
#include "io/h5_snapshot.hpp"
#include "io/io_test_helpers.hpp"
#include "run/run_output.hpp"
#include "support/support.hpp"

namespace gs {
namespace {

constexpr double kStep = 1e-4;

// 1000 spheres on a lattice, apart (no contacts), each with a velocity of
// its own, ids shuffled so that the store's order is not the id order.
SceneSpec free_flight_scene(const std::string& directory) {
  SceneSpec s = test::base_scene(2500, 1e4, 0.5, 0.5);
  s.effects = kFriction;  // a checkpoint with contact history rows (all free here)
  s.gravity = Vec3d();
  std::vector<ParticleId> ids(1000);
  std::iota(ids.begin(), ids.end(), ParticleId(0));
  std::shuffle(ids.begin(), ids.end(), std::mt19937(7));
  for (int k = 0; k < 1000; ++k) {
    const Vec3d at(-0.015 + 0.003 * (k % 10), -0.015 + 0.003 * (k / 10 % 10), -0.015 + 0.003 * (k / 100));
    const Vec3d v(0.01 * (k % 7 + 1), -0.02 * (k % 5), 0.005 * (k % 3 - 1));
    s.particles.push_back(test::particle(ids[std::size_t(k)], 0.001, at, v));
  }
  s.time_step = kStep;
  s.output.directory = directory;
  return s;
}

// Position of each particle, in id order, after `steps` steps of free flight.
std::vector<Vec3d> expected_positions(const SceneSpec& s, int steps) {
  std::vector<Vec3d> x(s.particles.size());
  for (const ParticleInit& p : s.particles) {
    Vec3d at = p.position;
    for (int k = 0; k < steps; ++k) at = at + p.velocity * kStep;
    x[p.id] = at;
  }
  return x;
}

void expect_positions(const std::vector<double>& flat, const std::vector<Vec3d>& expected, const std::string& what) {
  ASSERT_EQ(flat.size(), 3 * expected.size()) << what;
  int wrong = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const Vec3d got(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
    wrong += norm(got - expected[i]) > 1e-12;
  }
  EXPECT_EQ(wrong, 0) << what << ": rows not at their particle's position";
}

class RunOutputTest : public testing::TestWithParam<Backend> {};

TEST_P(RunOutputTest, BackToBackOutputsEachWriteTheirOwnParticles) {
  const std::string dir = testing::TempDir() + "/run_output_" + backend_name(GetParam());
  std::filesystem::remove_all(dir);
  const SceneSpec scene = free_flight_scene(dir);
  RunOptions o;
  o.backend = GetParam();
  constexpr int kStates = 5;  // the same particles after 0, 1, ... 4 steps
  std::vector<std::unique_ptr<Simulation>> at;
  for (int k = 0; k < kStates; ++k) {
    at.push_back(std::make_unique<Simulation>(scene, o));
    at.back()->run(k);
  }
  const std::unique_ptr<Transport> transport = make_single_transport();
  {
    RunOutput out(scene, dir, *transport, "");
    const auto start = Clock::now();
    // Each call refills the host arrays the previous file is still being
    // written from, unless it waits for that file first.
    for (int k = 0; k < kStates; ++k) out.snapshot(*at[std::size_t(k)]);
    out.checkpoint(*at[1]);
    out.checkpoint(*at[2]);
    out.finish();
    // The output's split: its parts are disjoint spans of these calls.
    const double wall = seconds_since(start);
    const RunOutput::Split& t = out.split();
    EXPECT_GT(t.host_copy, 0.0);
    EXPECT_GT(t.series, 0.0);
    EXPECT_GT(t.wall_records, 0.0);  // a frictional run collects its wall contacts' rows
    EXPECT_GE(t.waiting, 0.0);
    EXPECT_GE(t.mesh_loads, 0.0);
    EXPECT_LE(t.waiting + t.host_copy + t.wall_records + t.mesh_loads + t.series, wall);
  }
  std::vector<ParticleId> ids(scene.particles.size());
  std::iota(ids.begin(), ids.end(), ParticleId(0));
  for (int k = 0; k < kStates; ++k) {
    const std::string file = dir + "/" + snapshot_h5_name(k);
    expect_positions(test::read_h5<double>(file, "particles/position", H5T_NATIVE_DOUBLE), expected_positions(scene, k),
                     file);
    EXPECT_EQ(test::read_h5<ParticleId>(file, "particles/id", H5T_NATIVE_UINT32), ids) << file;
    EXPECT_EQ(test::read_h5_attribute<std::int64_t>(file, "/", "step", H5T_NATIVE_INT64), k) << file;
  }
  for (int k : {1, 2}) {
    const Checkpoint c = read_checkpoint(dir + "/" + checkpoint_h5_name(k));
    EXPECT_EQ(c.step, k);
    std::vector<double> flat;
    for (const Vec3d& x : c.particles.position) flat.insert(flat.end(), {x.x, x.y, x.z});
    expect_positions(flat, expected_positions(scene, k), "checkpoint " + std::to_string(k));
    EXPECT_EQ(c.particles.id, ids);
    EXPECT_EQ(c.history.partner, std::vector<ParticleId>(c.history.partner.size(), kNoPartner));
  }
  std::filesystem::remove_all(dir);
}

// 500 pairs of spheres pressed 0.1 mm into each other and sliding past each
// other (friction springs in every pair's history), ids shuffled; `slide`
// sets the speed of the slip.
SceneSpec sliding_pairs_scene(const std::string& directory, double slide) {
  SceneSpec s = free_flight_scene(directory);
  s.particles.clear();
  std::vector<ParticleId> ids(1000);
  std::iota(ids.begin(), ids.end(), ParticleId(0));
  std::shuffle(ids.begin(), ids.end(), std::mt19937(11));
  for (int j = 0; j < 500; ++j) {
    const Vec3d at(-0.015 + 0.006 * (j % 5), -0.015 + 0.003 * (j / 5 % 10), -0.015 + 0.003 * (j / 50));
    s.particles.push_back(test::particle(ids[std::size_t(2 * j)], 0.001, at, {0, slide, 0}));
    s.particles.push_back(test::particle(ids[std::size_t(2 * j + 1)], 0.001, at + Vec3d(0.0019, 0, 0), {0, -slide, 0}));
  }
  s.time_step = 1e-6;  // well below the contact time (about 7e-5 s)
  return s;
}

// The checkpoint file holds `sim`'s state now: its particles and history as
// the simulation gives them directly (not through RunOutput's arrays).
void expect_checkpoint_of(const std::string& file, const Simulation& sim, const std::string& what) {
  const Checkpoint c = read_checkpoint(file);
  const ParticleSnapshot s = sim.snapshot();
  const HostHistory h = sim.history();
  EXPECT_EQ(c.step, sim.step_count()) << what;
  EXPECT_TRUE(test::same_bits(c.particles.position, s.position)) << what;
  EXPECT_TRUE(test::same_bits(c.particles.velocity, s.velocity)) << what;
  EXPECT_TRUE(test::same_bits(c.particles.force, s.force)) << what;
  EXPECT_TRUE(test::same_bits(c.history.partner, h.partner)) << what;
  EXPECT_TRUE(test::same_bits(c.history.tangential, h.tangential)) << what;
  const auto touching = std::count_if(h.partner.begin(), h.partner.end(), [](ParticleId p) { return p != kNoPartner; });
  EXPECT_EQ(touching, 1000) << what << ": every sphere has its partner in its history";
}

// A checkpoint at the step of the last snapshot takes that snapshot's host
// copy of the particles and copies only the history (while the snapshot's
// file is written), where the snapshot was told it follows; any other state
// is copied anew: after a snapshot not told so (whose copy holds no forces),
// another simulation at the same step, or the same one a step later. (Three
// checkpoints of step 3 in a row: the newest two kept are files, not names
// listed twice, or the pruning would remove the file just written.)
TEST_P(RunOutputTest, CheckpointAtTheSnapshotsStateTakesItsParticles) {
  const std::string dir = testing::TempDir() + "/run_output_shared_" + backend_name(GetParam());
  std::filesystem::remove_all(dir);
  const SceneSpec scene = sliding_pairs_scene(dir, 0.05), other = sliding_pairs_scene(dir, -0.08);
  RunOptions o;
  o.backend = GetParam();
  Simulation a(scene, o), b(other, o);
  a.run(3);
  b.run(3);
  const std::unique_ptr<Transport> transport = make_single_transport();
  RunOutput out(scene, dir, *transport, "");
  const std::string at_3 = dir + "/" + checkpoint_h5_name(3), at_4 = dir + "/" + checkpoint_h5_name(4);
  out.snapshot(a, true);
  out.checkpoint(a);
  out.finish();
  expect_checkpoint_of(at_3, a, "the snapshot's state");
  out.snapshot(a);
  out.checkpoint(a);
  out.finish();
  expect_checkpoint_of(at_3, a, "the state of a snapshot without forces");
  out.snapshot(a, true);
  out.checkpoint(b);
  out.finish();
  expect_checkpoint_of(at_3, b, "another simulation at the snapshot's step");
  out.snapshot(a, true);
  a.run(1);
  out.checkpoint(a);
  out.finish();
  expect_checkpoint_of(at_4, a, "a step after the snapshot");
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Backends, RunOutputTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
