// Rank-count independence, run under mpiexec with 2, 3 or 4 ranks: the
// multi-rank state after N steps equals, bit for bit, a one-rank run of the
// same scene computed on every rank; migration keeps every particle and every
// contact history.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <tuple>

#include "comm/device_link.hpp"
#include "comm/domain_exchange.hpp"
#include "comm/records_codec.hpp"
#include "comm/scene_split.hpp"
#include "comm/snapshot_gather.hpp"
#include "io/state_digest.hpp"
#include "scene/fill_blocks.hpp"
#include "scene/generators.hpp"
#include "scene/particle_sources.hpp"
#include "support/support.hpp"
#include "walls/mesh_test_helpers.hpp"

namespace gs::test {
namespace {

Transport& world() {
  static std::unique_ptr<Transport> t = make_mpi_transport();
  return *t;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Contacts of each particle as partner id -> every history value, gathered on rank 0.
using ContactMap = std::map<ParticleId, std::map<ParticleId, std::vector<double>>>;

void append_value(std::vector<double>& to, const Vec3d& v) { to.insert(to.end(), {v.x, v.y, v.z}); }
void append_value(std::vector<double>& to, double v) { to.push_back(v); }

ContactMap contacts_of(const ParticleSnapshot& s, const HostHistory& h) {
  ContactMap m;
  const std::size_t k = std::size_t(h.slots);
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t slot = 0; slot < k; ++slot) {
      const std::size_t e = i * k + slot;
      if (h.partner[e] == kNoPartner) continue;
      std::vector<double>& values = m[s.id[i]][h.partner[e]];
      for_each_history_field(h, [&](const char*, unsigned, const auto& field) {
        if (!field.empty()) append_value(values, field[e]);
      });
    }
  return m;
}

ContactMap gathered_contacts(const Simulation& sim) {
  ParticleRecords r;
  r.id = sim.snapshot().id;
  r.history = sim.history();
  Bytes mine;
  encode_records(r, mine);
  ParticleSnapshot ids;
  HostHistory all;
  all.slots = r.history.slots;
  for (const Bytes& b : world().gather(mine)) {
    const ParticleRecords part = decode_records(b);
    ids.id.insert(ids.id.end(), part.id.begin(), part.id.end());
    all.partner.insert(all.partner.end(), part.history.partner.begin(), part.history.partner.end());
    for_each_history_field(all, part.history, [](const char*, unsigned, auto& to, const auto& from) {
      to.insert(to.end(), from.begin(), from.end());
    });
  }
  return contacts_of(ids, all);
}

std::vector<RemovedParticle> by_step_and_id(std::vector<RemovedParticle> r) {
  std::sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return std::tie(a.step, a.id) < std::tie(b.step, b.id); });
  return r;
}

// Every rank's removed particles on rank 0, by step and id.
std::vector<RemovedParticle> gathered_removed(Simulation& sim) {
  const std::vector<RemovedParticle> mine = sim.take_removed();
  Bytes b(mine.size() * sizeof(RemovedParticle));
  if (!mine.empty()) std::memcpy(b.data(), mine.data(), b.size());
  std::vector<RemovedParticle> all;
  for (const Bytes& part : world().gather(b)) {
    const std::size_t at = all.size();
    all.resize(at + part.size() / sizeof(RemovedParticle));
    if (!part.empty()) std::memcpy(all.data() + at, part.data(), part.size());
  }
  return by_step_and_id(all);
}

bool same_removals(const std::vector<RemovedParticle>& a, const std::vector<RemovedParticle>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].step != b[k].step || a[k].id != b[k].id || a[k].exit != b[k].exit || a[k].mass != b[k].mass) return false;
  return true;
}

// GPU ranks, each on a GPU of its own, exchanging over NCCL: on the device
// machine's multi-GPU kinds, with GS_TEST_BACKENDS naming cuda. Collective.
bool gpu_ranks_ready() {
  const std::vector<Backend> b = test_backends();
  if (std::find(b.begin(), b.end(), Backend::cuda) == b.end() || !nccl_available()) return false;
  const bool own_gpu = cuda_device_available() && select_cuda_device(world().local_rank());
  return world().min(own_gpu ? 1 : 0) == 1;
}

// Runs `scene` for `steps` on one rank and on every rank of the world, and
// compares on rank 0. On the CUDA backend the one-rank run is on each rank's
// own GPU, and the ranks move particles over NCCL.
void expect_rank_independent(const SceneSpec& scene, long long steps, RunOptions options = {}) {
  Simulation one(scene, options);
  one.run(steps);
  auto exchange = split_scene(scene, world());
  if (options.backend == Backend::cuda) exchange->use_device_link(make_nccl_link(world()));
  Simulation many(scene, options, exchange);
  many.run(steps);
  const ParticleSnapshot all = gather_snapshot(world(), many.snapshot());
  const ContactMap many_contacts = gathered_contacts(many);
  const std::vector<RemovedParticle> removed = gathered_removed(many);
  if (world().rank() != 0) return;
  const ParticleSnapshot ref = one.snapshot();
  const std::vector<RemovedParticle> ref_removed = by_step_and_id(one.take_removed());
  // The one-rank state's digest, for comparing builds (a refactor must not change it).
  std::printf("[ digest   ] %s: 0x%016" PRIx64 "\n", ::testing::UnitTest::GetInstance()->current_test_info()->name(),
              state_digest(ref, one.history()));
  ASSERT_EQ(all.size(), ref.size()) << "particles lost or duplicated";
  if (scene.inlets.empty()) {
    ASSERT_EQ(all.size() + removed.size(), particle_count(scene)) << "particles lost or duplicated";
  }
  EXPECT_TRUE(same_removals(removed, ref_removed)) << removed.size() << " removed on " << world().size()
                                                   << " ranks, " << ref_removed.size() << " on one";
  if (scene.has_exits()) {
    EXPECT_GT(ref_removed.size(), 0u) << "nothing was removed";
  }
  EXPECT_TRUE(same_bits(all.id, ref.id));
  EXPECT_TRUE(same_bits(all.position, ref.position)) << exchange->describe();
  EXPECT_TRUE(same_bits(all.velocity, ref.velocity));
  EXPECT_TRUE(same_bits(all.angular_velocity, ref.angular_velocity));
  EXPECT_TRUE(same_bits(all.force, ref.force));
  EXPECT_TRUE(same_bits(all.image, ref.image));  // periodic runs; empty otherwise
  const ContactMap ref_contacts = contacts_of(ref, one.history());
  EXPECT_GT(ref_contacts.size(), 0u);
  EXPECT_TRUE(ref_contacts == many_contacts) << "contact histories differ";
}

// Frictional glass with rolling resistance under gravity in a box [0, side]^2
// x [0, height] (open at the top), fp32, slabs along z; no particles yet.
SceneSpec frictional_box(double side, double height) {
  SceneSpec s = base_scene(2500, 2000, 0.5, 0.5);
  s.precision = Precision::fp32;
  s.effects = kFriction | kRollingResistance;
  s.pairs[0].rolling_friction = 0.1;
  s.gravity = {0, 0, -9.81};
  s.domain_min = {-0.001, -0.001, -0.001};
  s.domain_max = {side + 0.001, side + 0.001, height + 0.001};
  s.walls = {plane_wall({0, 0, 0}, {1, 0, 0}), plane_wall({side, 0, 0}, {-1, 0, 0}),
             plane_wall({0, 0, 0}, {0, 1, 0}), plane_wall({0, side, 0}, {0, -1, 0}), plane_wall({0, 0, 0}, {0, 0, 1})};
  s.decomposition.axis = 2;
  return s;
}

// Polydisperse (1:3) frictional spheres with rolling resistance settling in a
// box: the slabs cut the falling column, so particles cross boundaries.
SceneSpec settling_scene(DecompositionMethod method) {
  SceneSpec s = frictional_box(0.02, 0.04);
  RandomFillSpec fill;
  fill.region.min = {0.0015, 0.0015, 0.0015};
  fill.region.max = {0.0185, 0.0185, 0.0385};
  fill.count = 500;
  fill.size.kind = SizeSpec::Kind::uniform;
  fill.size.radius_min = 0.0004;
  fill.size.radius_max = 0.0012;
  fill.seed = 7;
  generate_random_fill(fill, s.particles);
  s.decomposition.method = method;
  s.time_step = 2e-5;
  return s;
}

TEST(RankIndependence, PolydisperseFrictionalSettlingWithSlabs) {
  RunOptions o;
  o.rebalance_interval = 200;  // the bed sinks into the lower slabs: re-balancing happens
  expect_rank_independent(settling_scene(DecompositionMethod::slabs), 1500, o);
}

TEST(RankIndependence, PolydisperseFrictionalSettlingWithMetis) {
  expect_rank_independent(settling_scene(DecompositionMethod::metis), 1500);
}

// A skin of half a diameter, five times the default, from the scene: the
// lists and the halo reach that far beyond contact on every rank, and the
// result is the one rank's bit for bit. (The decomposition's coarse cells
// take the skin too, comm/scene_split.cpp; here the slabs are thicker than
// the halo either way, so this run would not notice cells left narrower:
// ThinSlabsOfAWideSkin below does.)
TEST(RankIndependence, PolydisperseFrictionalSettlingWithAWideSkin) {
  SceneSpec s = settling_scene(DecompositionMethod::slabs);
  s.verlet_skin = 0.5;
  expect_rank_independent(s, 1500);
}

// Slabs as thin as the halo: 2 mm spheres thrown about at up to 0.5 m/s in
// a closed box 12.5 mm tall along the slabs' axis, under ten times gravity
// (they come to lie on the floor, touching), at a skin of half a diameter.
// The split's coarse cells must be at least 3 mm (a diameter and the skin,
// as far as ghosts reach): four layers, so on four ranks every slab is one
// layer and a ghost comes from the next slab only. Cells made at the default
// skin (2.2 mm: five layers of 2.5 mm) would leave a slab thinner than the
// halo, whose ghosts could belong to a rank two slabs away, which is not
// among a rank's neighbours; the run alone seldom meets such a pair (it must
// come into contact within one list's life), so the cells are checked too.
TEST(RankIndependence, ThinSlabsOfAWideSkin) {
  SceneSpec s = frictional_box(0.02, 0.0105);
  s.gravity = {0, 0, -98.1};
  s.walls.push_back(plane_wall({0, 0, 0.0105}, {0, 0, -1}));  // a lid
  RandomFillSpec fill;
  fill.region.min = {0.001, 0.001, 0.001};
  fill.region.max = {0.019, 0.019, 0.0095};
  fill.count = 150;
  fill.size.radius_min = fill.size.radius_max = 0.001;
  fill.seed = 5;
  generate_random_fill(fill, s.particles);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> speed(-0.5, 0.5);
  for (ParticleInit& p : s.particles) p.velocity = {speed(random), speed(random), speed(random)};
  s.verlet_skin = 0.5;
  s.time_step = 2e-5;
  const auto split = split_scene(s, world());
  EXPECT_GE(split->decomposition().grid().min_edge(), 0.002 * (1 + s.verlet_skin)) << split->describe();
  expect_rank_independent(s, 1000);
}

// A random fill kept as its source, cut into two blocks along x: each rank
// makes only the blocks that meet its slab (a window at setup; on 3 and 4
// ranks the outer slabs meet one block each), and the particles, and the
// run, are those of one rank.
TEST(RankIndependence, RandomFillBlocksMadePerRank) {
  SceneSpec s = frictional_box(0.07, 0.02);
  RandomFillSpec fill;
  fill.region.min = {0.0015, 0.0015, 0.0015};
  fill.region.max = {0.0685, 0.0185, 0.0185};
  fill.count = 8200;
  fill.size.radius_min = fill.size.radius_max = 0.0004;
  fill.seed = 9;
  fill.tmpl.velocity = {0, 0, -2};  // thrown at the floor: contacts within the run
  s.fills.push_back(make_fill_source(fill, 0));
  ASSERT_EQ(s.fills.front().blocks.count(), 2u);
  s.decomposition.axis = 0;
  s.time_step = 2e-5;
  expect_rank_independent(s, 80);
}

// An inlet above a settling bed, its region cut by the slabs (along x): every
// rank draws the same candidates, marks those its own particles block, and
// the ranks that own the accepted positions append them; the result is the
// one-rank run's, ids included. Empty at first, then a stream that lands on
// the bed across the slab boundaries.
SceneSpec inlet_scene() {
  SceneSpec s = frictional_box(0.02, 0.05);
  RandomFillSpec fill;
  fill.region.min = {0.0015, 0.0015, 0.0015};
  fill.region.max = {0.0185, 0.0185, 0.0185};
  fill.count = 200;
  fill.size.kind = SizeSpec::Kind::uniform;
  fill.size.radius_min = 0.0004;
  fill.size.radius_max = 0.0012;
  fill.seed = 3;
  generate_random_fill(fill, s.particles);
  InletSpec in;
  in.region.min = {0.001, 0.001, 0.03};
  in.region.max = {0.019, 0.019, 0.045};
  in.size.kind = SizeSpec::Kind::uniform;
  in.size.radius_min = 0.0004;
  in.size.radius_max = 0.0008;
  in.rate = 50000;
  in.interval_steps = 20;
  in.tmpl.velocity = {0, 0, -0.5};
  in.velocity_spread = 0.2;
  in.seed = 5;
  s.inlets.push_back(in);
  s.decomposition.axis = 0;
  s.time_step = 2e-5;
  return s;
}
constexpr long long kInletSteps = 1000;  // some 1000 particles inserted

TEST(RankIndependence, InletFeedsBedAcrossSlabs) { expect_rank_independent(inlet_scene(), kInletSteps); }

// Staged walls (docs/SCENES.md, walls): spheres thrown down through an
// orifice plate onto a shaking gate that opens, a side wall pushed by a
// velocity table, and a cone around them; every rank poses every wall alike.
TEST(RankIndependence, StagedWallsPlatesAndCone) {
  SceneSpec s = settling_scene(DecompositionMethod::slabs);
  // Those clear of the plate, the cone and the shifted side wall at t = 0.
  std::vector<ParticleInit> clear;
  for (ParticleInit p : s.particles) {
    const double rho = std::hypot(p.position.x - 0.01, p.position.y - 0.01);
    const double from_cone = std::abs(0.006 + 0.225 * p.position.z - rho) * std::cos(std::atan(0.225));
    if (p.position.z - p.radius < 0.0085 || from_cone < p.radius + 1e-4 || p.position.x - p.radius < 0.0025) continue;
    p.id = ParticleId(clear.size());
    p.velocity = {0, 0, -0.6};
    clear.push_back(p);
  }
  s.particles = clear;
  Wall orifice = plane_wall({0.01, 0.01, 0.008}, {0, 0, 1});
  orifice.kind = WallKind::plate;
  orifice.radius = 0.03;
  orifice.hole_half[0] = 0.004;
  Wall gate = plane_wall({0.01, 0.01, 0.004}, {0, 0, 1});
  gate.kind = WallKind::plate;
  gate.radius = 0.009;
  Wall cone = plane_wall({0.01, 0.01, 0.0}, {0, 0, 1});
  cone.kind = WallKind::cone;
  cone.radius = 0.006;
  cone.length = 0.04;
  cone.end_radius = 0.015;
  s.walls[0].point.x = 0.002;  // the side wall pushed in from x = 0.002 by the table
  for (const Wall& w : {orifice, gate, cone}) s.walls.push_back(w);
  s.wall_timelines.resize(s.walls.size());
  s.wall_timelines[0].velocity = make_rate_table({0, 0.005, 0.01}, {Vec3d(), Vec3d(0.05, 0, 0), Vec3d()});
  Timeline& g = s.wall_timelines[s.walls.size() - 2];
  g.active.until = 0.012;
  g.oscillation.amplitude = {0, 0, 0.0003};
  g.oscillation.frequency = 60;
  expect_rank_independent(s, 1000);
}

// A paddle turning about an axis in the slab boundary, through a lattice of
// spheres at rest without gravity: the spheres ahead of it are struck on
// both ranks' sides. Only the mesh's drift calls for the rebuilds of the halo
// and of the lists its strikes need (walls/mesh_near.hpp); every rank poses
// the mesh alike and rebuilds at the same steps.
TEST(RankIndependence, PaddleSweepsSpheresAtRestAcrossSlabs) {
  SceneSpec s = base_scene(2500, 2000, 0.5, 0.4);
  s.effects = kFriction;
  s.domain_min = {-0.01, -0.01, -0.004};
  s.domain_max = {0.01, 0.01, 0.004};
  LatticeSpec l;
  l.radius = 0.0005;
  l.spacing = 0.0015;
  l.min = {-0.009, -0.009, -0.003};
  l.max = {0.009, 0.009, 0.003};
  std::vector<ParticleInit> lattice;
  generate_lattice(l, lattice);
  for (ParticleInit p : lattice) {
    if (std::abs(p.position.y) < 0.0006) continue;  // the paddle's plane
    p.id = ParticleId(s.particles.size());
    s.particles.push_back(p);
  }
  // In the plane y = 0 from x = -8 mm to 8 mm, turning about z at 600 rpm.
  const FlatSquare paddle =
      make_flat_square(8, 0.002, 0.2, Rotation(Vec3d(1, 0, 0), M_PI / 2), Vec3d(-0.008, 0, -0.008), 9);
  add_mesh(s.meshes, paddle.mesh, 0, rotation_at_rpm(Vec3d(), Vec3d(0, 0, 1), 600));
  s.decomposition.axis = 0;
  s.time_step = 5e-6;
  expect_rank_independent(s, 1000);
}

// Two lattices flying into each other across the slab boundary (no gravity,
// no walls): particles stream through the boundary in both directions,
// collide on both sides of it, and keep their friction history as they cross.
SceneSpec streaming_scene() {
  SceneSpec s = base_scene(2500, 2000, 0.8, 0.4);
  s.effects = kFriction;
  s.precision = Precision::fp64;
  s.domain_min = {-0.03, -0.01, -0.01};
  s.domain_max = {0.03, 0.01, 0.01};
  // The right lattice is offset by 0.9 mm in y: its spheres pass between the
  // left ones, grazing them (overlap 0.1 mm), so the flows cross each other.
  for (int side = 0; side < 2; ++side) {
    LatticeSpec l;
    l.tmpl.velocity = {side == 0 ? 1.0 : -1.0, 0, 0};
    l.radius = 0.0005;
    l.spacing = 0.0022;
    const double shift = side == 0 ? 0.0 : 0.0009;
    l.min = {side == 0 ? -0.012 : 0.0006, -0.0044 + shift, -0.0044};
    l.max = {side == 0 ? -0.0006 : 0.012, 0.0044 + shift, 0.0044};
    generate_lattice(l, s.particles);
  }
  for (std::size_t i = 0; i < s.particles.size(); ++i) s.particles[i].id = ParticleId(i);
  s.decomposition.axis = 0;
  s.time_step = 5e-6;
  return s;
}
constexpr long long kStreamingSteps = 380;  // 1.9 ms: the second rows of each side meet

TEST(RankIndependence, StreamsThroughSlabBoundaryBothWays) {
  expect_rank_independent(streaming_scene(), kStreamingSteps);
}

// Periodic in x, slabs along x, which wrap: the two lattices fly apart,
// cross the periodic faces (the boundary between the last slab and the
// first) and collide there, grazing, with friction; on every rank count
// the positions, image counts and springs are those of one rank.
SceneSpec periodic_streaming_scene() {
  SceneSpec s = streaming_scene();
  for (ParticleInit& p : s.particles) p.velocity.x = -p.velocity.x;  // towards the faces
  s.domain_min.x = -0.016;
  s.domain_max.x = 0.016;
  s.periodic_axes = 1u;
  return s;
}
constexpr long long kPeriodicSteps = 1400;  // 7 mm each way: the outer rows meet across the faces and cross them

TEST(RankIndependence, PeriodicStreamsAcrossWrappingSlabs) {
  const SceneSpec s = periodic_streaming_scene();
  expect_rank_independent(s, kPeriodicSteps);
  if (world().rank() != 0) return;
  Simulation one(s, RunOptions{});
  one.run(kPeriodicSteps);
  int crossed = 0;
  for (const ImageCount& n : one.snapshot().image) crossed += n.x != 0 ? 1 : 0;
  EXPECT_GT(crossed, 20);
}

// The same with METIS parts: the parts across the periodic faces trade ghosts.
TEST(RankIndependence, PeriodicStreamsAcrossMetisParts) {
  SceneSpec s = periodic_streaming_scene();
  s.decomposition.method = DecompositionMethod::metis;
  expect_rank_independent(s, kPeriodicSteps);
}

// The same two lattices, faster, in a domain open on every side: removed at
// the faces as they stream out (or are scattered out), on whichever rank.
TEST(RankIndependence, StreamsOutThroughOpenFaces) {
  SceneSpec s = streaming_scene();
  s.domain_min.x = -0.014;
  s.domain_max.x = 0.014;
  s.open_faces = 63;  // all six
  for (ParticleInit& p : s.particles) p.velocity.x *= 3;
  expect_rank_independent(s, 700);  // 3.5 ms: scattered ones have left sideways, the rest still cross
}

// Settling into a drain in a corner of the floor: removed there on the
// lowest slab's rank, while the bed re-balances.
TEST(RankIndependence, SettlesIntoACornerDrain) {
  SceneSpec s = settling_scene(DecompositionMethod::slabs);
  OutletRegion drain;
  drain.min = {0, 0, 0};
  drain.max = {0.008, 0.008, 0.004};
  s.outlets.push_back({"drain", drain});
  RunOptions o;
  o.rebalance_interval = 200;
  expect_rank_independent(s, 1500, o);
}

// The hysteretic normal law keeps each contact's peak overlap in its history
// (its transport between ranks: tests/engine/test_particle_message.cpp).
TEST(RankIndependence, HystereticSettlingWithSlabs) {
  SceneSpec s = settling_scene(DecompositionMethod::slabs);
  s.model = ContactModel::hysteretic_linear;
  s.time_step = 5e-6;  // its unloading spring is 1/e^2 = 4 times the loading one
  expect_rank_independent(s, 6000);
}

// A compressed lattice (spacing 0.98 diameters, alternate spheres 1 %
// smaller) springing apart under gravity with friction and rolling
// resistance: every sphere starts with up to six contacts, so the order of
// each sum matters (two terms would add the same either way).
SceneSpec compressed_lattice_scene() {
  SceneSpec s = frictional_box(0.012, 0.012);
  s.walls.push_back(plane_wall({0, 0, 0.012}, {0, 0, -1}));  // a lid: the lattice springs upwards too
  LatticeSpec l;
  l.radius = 0.0005;
  l.spacing = 0.00098;
  l.min = {0.0006, 0.0006, 0.0006};
  l.max = {0.0114, 0.0114, 0.0114};
  generate_lattice(l, s.particles);
  for (std::size_t i = 0; i < s.particles.size(); i += 2) s.particles[i].radius = 0.000495;
  s.time_step = 1e-5;
  return s;
}
constexpr long long kCompressedSteps = 400;

TEST(RankIndependence, CompressedLatticeWithManyContacts) {
  expect_rank_independent(compressed_lattice_scene(), kCompressedSteps);
}

// The checkpoint's gather (comm/snapshot_gather.cpp): every rank's history
// rows at their particle's place in id order on rank 0, bitwise the one-rank
// run's history (in id order by its own path, no gather), twice into the same
// arrays (kept from call to call, as RunOutput keeps them).
TEST(RankIndependence, GatheredHistoryIsTheOneRanksInIdOrder) {
  SceneSpec scene = compressed_lattice_scene();
  std::vector<ParticleId> ids(scene.particles.size());  // shuffled: every rank's ids spread over the whole range
  std::iota(ids.begin(), ids.end(), ParticleId(0));
  std::shuffle(ids.begin(), ids.end(), std::mt19937(5));
  for (std::size_t i = 0; i < ids.size(); ++i) scene.particles[i].id = ids[i];
  Simulation one(scene, {});
  one.run(50);
  Simulation many(scene, {}, split_scene(scene, world()));
  many.run(50);
  // This rank's rows handed over last first: the gather puts them in order.
  std::vector<ParticleId> mine = many.snapshot().id;
  HostHistory local = many.history();
  const std::size_t width = std::size_t(local.slots), n = mine.size();
  std::reverse(mine.begin(), mine.end());
  auto reverse_rows = [&](auto& v) {
    for (std::size_t i = 0; i < n / 2; ++i)
      for (std::size_t k = 0; k < width; ++k) std::swap(v[i * width + k], v[(n - 1 - i) * width + k]);
  };
  reverse_rows(local.partner);
  reverse_rows(local.tangential);
  HostHistory all;
  for (int call = 0; call < 2; ++call) {  // no ASSERT: rank 0 must reach the second (collective) call too
    std::string error;
    try {
      gather_history(world(), mine, local, all);
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (world().rank() != 0) continue;
    EXPECT_EQ(error, "") << "call " << call;
    const HostHistory ref = one.history();
    EXPECT_EQ(all.slots, ref.slots);
    EXPECT_EQ(all.partner, ref.partner) << "call " << call;
    EXPECT_TRUE(all.tangential.size() == ref.tangential.size() &&
                std::memcmp(all.tangential.data(), ref.tangential.data(), ref.tangential.size() * sizeof(Vec3d)) == 0)
        << "call " << call;
    const auto touching = std::count_if(ref.partner.begin(), ref.partner.end(), [](ParticleId p) { return p != kNoPartner; });
    EXPECT_GT(touching, std::ptrdiff_t(ref.partner.size() / 4)) << "a bed in contact";
  }
}

// A lattice kept as its description: each rank generates and holds only the
// particles it owns, and the run is the one-rank run, bit for bit.
TEST(RankIndependence, LatticeSetUpHoldsOnlyEachRanksOwn) {
  SceneSpec s = frictional_box(0.012, 0.03);
  LatticeSpec l;
  l.radius = 0.0005;
  l.spacing = 0.0011;
  l.min = {0.0006, 0.0006, 0.0006};
  l.max = {0.0114, 0.0114, 0.025};
  const std::size_t n = lattice_count(l);
  s.lattices.push_back({l, 0, n});
  s.time_step = 1e-5;
  const auto exchange = split_scene(s, world());
  Simulation many(s, RunOptions{}, exchange);
  const ParticleSnapshot mine = many.snapshot();
  if (world().size() > 1) {
    EXPECT_LT(mine.size(), n) << "a rank holds every particle";
  }
  for (const Vec3d& x : mine.position) EXPECT_TRUE(exchange->owns(x));
  many.run(20);
  const ParticleSnapshot all = gather_snapshot(world(), many.snapshot());
  if (world().rank() != 0) return;
  Simulation one(s, RunOptions{});
  one.run(20);
  const ParticleSnapshot ref = one.snapshot();
  ASSERT_EQ(all.size(), n) << "particles lost or duplicated";
  EXPECT_TRUE(same_bits(all.id, ref.id));
  EXPECT_TRUE(same_bits(all.position, ref.position));
  EXPECT_TRUE(same_bits(all.velocity, ref.velocity));
}

// The same scenes on GPU ranks over NCCL against one GPU: bitwise too, since
// each particle's sum runs in partner-id order on either backend.
class RankIndependenceOnGpus : public testing::Test {
 protected:
  void SetUp() override {
    if (!gpu_ranks_ready()) GTEST_SKIP() << "needs GS_TEST_BACKENDS with cuda, NCCL, and a GPU per rank";
    options.backend = Backend::cuda;
  }
  RunOptions options;
};

TEST_F(RankIndependenceOnGpus, PolydisperseFrictionalSettlingWithSlabs) {
  options.rebalance_interval = 200;
  expect_rank_independent(settling_scene(DecompositionMethod::slabs), 1500, options);
}

TEST_F(RankIndependenceOnGpus, PolydisperseFrictionalSettlingWithMetis) {
  expect_rank_independent(settling_scene(DecompositionMethod::metis), 1500, options);
}

TEST_F(RankIndependenceOnGpus, CompressedLatticeWithManyContacts) {
  expect_rank_independent(compressed_lattice_scene(), kCompressedSteps, options);
}

TEST_F(RankIndependenceOnGpus, StreamsThroughSlabBoundaryBothWays) {
  expect_rank_independent(streaming_scene(), kStreamingSteps, options);
}

TEST_F(RankIndependenceOnGpus, PeriodicStreamsAcrossWrappingSlabs) {
  expect_rank_independent(periodic_streaming_scene(), kPeriodicSteps, options);
}

TEST_F(RankIndependenceOnGpus, InletFeedsBedAcrossSlabs) {
  expect_rank_independent(inlet_scene(), kInletSteps, options);
}

}  // namespace
}  // namespace gs::test
