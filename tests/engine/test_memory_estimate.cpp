// estimate_memory (engine/memory_estimate.hpp) against the layout listed by
// hand, and against the high-water mark of a run's allocations on the CPU
// backend (whose arrays are the GPU's, less CUB's storage, plus its own for
// computing each pair once and its wider sort keys: MemoryEstimate::cpu_extra_bytes): a persistent
// array the estimate does not know of, or a transient one that stays (sort
// keys, fp64 list references), shows as bytes per particle it cannot account for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "backend/memory.hpp"
#include "engine/memory_estimate.hpp"
#include "io/checkpoint.hpp"
#include "io/restart.hpp"
#include "scene/particle_sources.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

// A simple-cubic lattice of side^3 spheres of 1 mm radius, `spacing` apart
// (default: 1 um gaps, so none touch), no walls and no gravity: each sphere
// has its face neighbours within the skin (the next are 2.83 mm away),
// 6 side^3 - 6 side^2 list entries in all.
SceneSpec lattice_scene(int side, unsigned effects, double spacing = 0.002001) {
  SceneSpec scene = base_scene(2500, 2000, 0.5, 0.5);
  scene.precision = Precision::fp32;
  scene.effects = effects;
  scene.gravity = {0, 0, 0};
  scene.time_step = 1e-5;
  scene.domain_min = {-0.0165, -0.0165, -0.0165};  // a tight box: few cells (up to side 16, and its drift)
  scene.domain_max = {0.0175, 0.0165, 0.0165};
  ParticleId id = 0;
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x)
        scene.particles.push_back(
            particle(id++, 0.001, {-0.015 + spacing * x, -0.015 + spacing * y, -0.015 + spacing * z}));
  return scene;
}

// The CPU's bytes per list entry for computing each pair once, in fp32: a
// reverse entry 4, a load (force and torque) 24, a touching flag 1.
constexpr double kCpuPairEntry = 4 + 24 + 1;

// Per particle, from the declarations: id 4, material and marker 1 each,
// radius, mass and inertia 4 each, position, velocity and angular velocity
// 24 each (no orientation: the scene's snapshots do not hold it); fp32
// force and torque 12 each; per list entry a touching flag and a spring
// (13), a surface row's index (4) and no row (no wall is near); Verlet list
// offsets 4, fp32 reference 12, 12 entries of 4. A rebuild's peak, beyond
// that, with history: the kept contacts, each pair's by one side (halved
// rows: engine/pair_keep.hpp), 6 of a partner id and a spring (96), their
// offsets 4 and the origin rows 4 (kept before the sort: no cell order
// beside them), the old references (12) and the force and torque (24)
// freed; without history none: the sort's phase (the cell order 4, a GPU's
// cell sort, 32-bit keys of the cell alone and their second buffer and the
// indices' second buffer, 12) and the fill's (the cell order and the new
// entries) come after the old list's entries and references are freed. The
// CPU's own per entry: kCpuPairEntry; with history its rebuild's peak comes
// later than a GPU's, when the kept contacts are merged into the new list
// (its reverse entries, freed with the old list, set again), without the
// origin rows: 4 bytes per particle fewer.
TEST(MemoryEstimate, FrictionalFp32LayoutByHand) {
  const MemoryEstimate m = estimate_memory(lattice_scene(2, kFriction));
  EXPECT_EQ(m.field_bytes, 4 + 1 + 1 + 3 * 4 + 3 * 24);
  EXPECT_EQ(m.force_bytes, 24);
  EXPECT_EQ(m.surface_row_share, 0);
  EXPECT_EQ(m.history_bytes, 12 * 13 + 4);
  EXPECT_EQ(m.list_bytes, 4 + 12 + 12 * 4);
  EXPECT_EQ(m.build_bytes, 12 / 2 * (4 + 12) + 4 + 4 - 12 - 24);
  EXPECT_EQ(m.bytes_per_particle, 90 + 24 + 160 + 64 + 68);
  EXPECT_EQ(m.cpu_extra_bytes, 12 * kCpuPairEntry - 4);
  const MemoryEstimate none = estimate_memory(lattice_scene(2, 0));
  EXPECT_EQ(none.history_bytes, 0);
  EXPECT_EQ(none.force_bytes, 12);  // no torque without friction
  EXPECT_EQ(none.field_bytes, 90 - 24);  // nor a spin
  EXPECT_EQ(none.build_bytes, 0);
  EXPECT_EQ(none.output_bytes, 24);  // an output's chunk: the positions whole, 8 spheres (under 1 MiB)
  EXPECT_EQ(none.bytes_per_particle, 66 + 12 + 64 + 24);
  EXPECT_EQ(none.cpu_extra_bytes, 12 * kCpuPairEntry - 24);
  EXPECT_EQ(estimate_memory(lattice_scene(128, 0)).output_bytes, 24.0 / 32);  // 2e6 spheres: a 32nd of the positions
  EXPECT_EQ(estimate_memory(lattice_scene(64, 0)).output_bytes, double(1 << 20) / (64 * 64 * 64));  // 1 MiB
  SceneSpec leaving = lattice_scene(2, 0);
  leaving.open_faces = 1u;  // particles leave through the domain's lower x face: the ids need not stay dense
  const MemoryEstimate open = estimate_memory(leaving);
  EXPECT_EQ(open.output_bytes, 4 + 12);  // the order by id and its sort's buffers
  EXPECT_EQ(open.bytes_per_particle, 66 + 12 + 64 + 16);
  EXPECT_EQ(open.cpu_extra_bytes, 12 * kCpuPairEntry + 4 - 16);
  EXPECT_EQ(estimate_memory([] {
              SceneSpec s = lattice_scene(2, kFriction);
              s.open_faces = 1u;
              return s;
            }()).bytes_per_particle,
            m.bytes_per_particle);  // with history a build's phase is the larger
  SceneSpec spinning = lattice_scene(2, 0);
  spinning.particles.front().angular_velocity = {0, 0, 1};
  EXPECT_EQ(estimate_memory(spinning).field_bytes, 90);  // a sphere that starts spinning keeps its spin
  SceneSpec with_orientations = lattice_scene(2, kFriction);
  with_orientations.output.fields = {"position", "orientation"};
  EXPECT_EQ(estimate_memory(with_orientations).field_bytes, 90 + 16);
}

// A floor 1 mm under the lower layer's centres of the side-2 lattice: its
// four spheres are within the reach of a radius and the skin (1.2 mm), the
// upper four (3 mm) are not. Half the spheres hold a row of 4 surface slots of
// 16 bytes, with room for a quarter more, and at a build a new copy of its
// largest array (the springs, 12 bytes a slot).
TEST(MemoryEstimate, SurfaceRowsForTheSpheresNearAWall) {
  SceneSpec scene = lattice_scene(2, kFriction);
  scene.walls = {plane_wall({0, 0, -0.016}, {0, 0, 1})};
  const MemoryEstimate m = estimate_memory(scene);
  EXPECT_EQ(m.surface_row_share, 0.5);
  EXPECT_EQ(m.history_bytes, 12 * 13 + 4 + 1.25 * 0.5 * 4 * (16 + 12));
  scene.walls[0].point.z = -0.0163;  // 1.3 mm: out of reach
  EXPECT_EQ(estimate_memory(scene).surface_row_share, 0);
}

// The peak of a CPU run of `scene` over `steps` steps, per particle, what
// the run then holds, its pair contacts at the end and its neighbour builds.
struct Measured {
  double bytes_per_particle = 0;
  double held_per_particle = 0;
  double contacts_per_particle = 0;
  long long builds = 0;
};
Measured measure(const SceneSpec& scene, long long steps) {
  backend_reset_peak(Backend::cpu);
  const std::size_t before = backend_peak_bytes(Backend::cpu);
  Simulation sim(scene, RunOptions{Backend::cpu});
  sim.run(steps);
  const double n = double(sim.particle_count());
  Measured got{double(backend_peak_bytes(Backend::cpu) - before) / n, double(sim.device_bytes()) / n, 0,
               sim.neighbour_builds()};
  long long contacts = 0;
  for (const std::uint16_t c : sim.snapshot().contacts) contacts += c;
  got.contacts_per_particle = double(contacts) / n;
  return got;
}

// The run's peak against the estimate with the lattice's own list entries
// (the estimate assumes 12), each 4 bytes in the list, with friction 13 of
// pair history, and kCpuPairEntry of the CPU's own. No sphere touches, so
// no contact is kept at a rebuild, and no phase of a rebuild holds more than
// the run holds between rebuilds: the old list's references (and, without
// history, its entries) and the CPU's reverse entries are freed before the
// cell list and its sort's buffers (20 bytes per particle on the CPU) come,
// and those are freed before the references are set again. A static bed
// builds its list once; a bed drifting as one body (the same neighbours
// throughout) rebuilds its list every 20 steps and is re-sorted at the
// rebuild after step 25, a component of a field at a time (8 bytes per
// particle, not a position's 24). A buffer grown by copying (its old and new
// storage at once), the old list's entries kept beside the cell list, or the
// sort's buffers kept beside the new list shows as 4 bytes or more at the
// peak; the cell list or a staging buffer held between rebuilds shows in
// what the run holds at the end.
TEST(MemoryEstimate, MatchesTheRunsPeakOnTheCpu) {
  const int side = 16;
  const double entries = 6.0 - 6.0 / side;
  for (const unsigned effects : {unsigned(kFriction), 0u})
    for (const bool drift : {false, true}) {
      SceneSpec scene = lattice_scene(side, effects);
      if (drift) {
        for (ParticleInit& p : scene.particles) p.velocity = {0.5, 0, 0};  // 5 um a step, half the skin in 20
      }
      const MemoryEstimate m = estimate_memory(scene);
      const Measured got = measure(scene, drift ? 60 : 20);
      if (drift) {
        EXPECT_GE(got.builds, 2);
      }
      const double missing = kEstimatedListEntries - entries, pair_entry = effects != 0 ? 1 + 12 : 0;
      EXPECT_EQ(got.contacts_per_particle, 0);  // so the kept contacts take no room
      const double held = m.bytes_per_particle - m.transient_bytes() - missing * (4 + pair_entry) + entries * kCpuPairEntry;
      // Within the cell offsets (the estimate's cells, one diameter, are more
      // than the run's) and a byte per particle: the fault flag, the pair
      // table, alignment.
      EXPECT_GE(got.bytes_per_particle, held) << "effects " << effects << ", drift " << drift;
      EXPECT_LT(got.bytes_per_particle, held + m.cell_bytes / double(scene.particles.size()) + 1)
          << "effects " << effects << ", drift " << drift << ", builds " << got.builds << ", contacts "
          << got.contacts_per_particle << ", held " << got.held_per_particle;
      EXPECT_LT(got.held_per_particle, held + 1) << "effects " << effects << ", drift " << drift;
    }
}

// A rebuild keeps only the touching contacts, in the staging buffer, and
// frees the old list's table before the new list is built: a periodic
// lattice pressed 20 um into each of its 6 neighbours (balanced, so the same
// contacts throughout), drifting as one body, rebuilt every 20 steps. Its
// peak is what it holds between rebuilds with, while the kept contacts are
// merged into the new list, 6 contacts, each pair's kept by the side of
// lower id (halved rows: one rank, every partner owned), so 3 of 16 bytes
// in the kept table, and their offsets (4) in place of the old list's references (12)
// and of the forces and torques (24: a build in a step does without them,
// and holds 24 bytes per particle more where it does not): the
// estimate with 6 entries and 6 contacts instead of 12, and the CPU's
// kCpuPairEntry per entry (a GPU's peak comes earlier, while the contacts are
// kept, beside the origin rows, which the CPU's reverse entries, freed
// then, outweigh). Held beside the new list, the old list's
// table (17 bytes per entry and its offsets) would add 110 bytes per particle.
TEST(MemoryEstimate, RebuildHoldsTheTouchingContactsOnly) {
  const int side = 12;
  const double spacing = 0.00198;
  SceneSpec scene = lattice_scene(side, kFriction, spacing);
  scene.periodic_axes = 7;
  scene.domain_min = {-0.015 - 0.5 * spacing, -0.015 - 0.5 * spacing, -0.015 - 0.5 * spacing};
  scene.domain_max = {scene.domain_min.x + side * spacing, scene.domain_min.y + side * spacing,
                      scene.domain_min.z + side * spacing};
  for (ParticleInit& p : scene.particles) p.velocity = {0.5, 0, 0};
  const MemoryEstimate m = estimate_memory(scene);
  const Measured got = measure(scene, 60);
  EXPECT_GE(got.builds, 3);
  ASSERT_EQ(got.contacts_per_particle, 6);
  const double entries = 6, contacts = 6, missing = kEstimatedListEntries - entries;
  const double held = m.bytes_per_particle - m.transient_bytes() - missing * (4 + 1 + 12) + entries * kCpuPairEntry;
  const double keeping = contacts / 2 * (4 + 12) + 4 - 12 - 24;
  EXPECT_GE(got.bytes_per_particle, held + keeping);
  EXPECT_LT(got.bytes_per_particle, held + keeping + m.cell_bytes / double(scene.particles.size()) + 1)
      << "builds " << got.builds << ", held " << got.held_per_particle;
}

// A wider skin lists more neighbours: at half a diameter a sphere of the
// gapped lattice (side 12) lists its edge neighbours too (2.83 mm away,
// within 3 mm), 15.6 entries on average instead of 5.5, each 4 bytes in the
// list, 13 of pair history and kCpuPairEntry of the CPU's own. The
// estimate, which grows its entries with the cube of (1 + skin), grows at
// least as much as the run's peak (at a fixed 12 entries it would not grow).
TEST(MemoryEstimate, AWiderSkinIsCounted) {
  const SceneSpec narrow = lattice_scene(12, kFriction);
  SceneSpec wide = narrow;
  wide.verlet_skin = 0.5;
  const double grown = measure(wide, 5).bytes_per_particle - measure(narrow, 5).bytes_per_particle;
  EXPECT_NEAR(grown, (15.6 - 5.5) * (4 + 13 + kCpuPairEntry), 20);
  const MemoryEstimate a = estimate_memory(narrow), b = estimate_memory(wide);
  EXPECT_GE(b.bytes_per_particle + b.cpu_extra_bytes - a.bytes_per_particle - a.cpu_extra_bytes, grown);
}

// At a snapshot or checkpoint the particles touching a wall are selected with
// their history (ParticleMover::wall_contact_history): the output then holds,
// beside the run, their indices and one field of their history at a time
// (the 12-byte springs of 12 slots at most), not an index per particle.
TEST(MemoryEstimate, OutputHoldsOnlyTheWallContacts) {
  const int side = 16;
  SceneSpec scene = lattice_scene(side, kFriction);
  const double face = 0.0159;  // the outer spheres 0.1 mm into the walls
  scene.walls = {plane_wall({-face, 0, 0}, {1, 0, 0}), plane_wall({face, 0, 0}, {-1, 0, 0}),
                 plane_wall({0, -face, 0}, {0, 1, 0}), plane_wall({0, face, 0}, {0, -1, 0}),
                 plane_wall({0, 0, -face}, {0, 0, 1}), plane_wall({0, 0, face}, {0, 0, -1})};
  Simulation sim(scene, RunOptions{Backend::cpu});
  sim.run(5);
  backend_reset_peak(Backend::cpu);
  const std::size_t held = backend_peak_bytes(Backend::cpu);
  const ParticleRecords r = sim.wall_contact_history();
  const double m = double(r.id.size());
  ASSERT_EQ(r.id.size(), std::size_t(side * side * side - (side - 2) * (side - 2) * (side - 2)));  // the outer shell
  const double output = double(backend_peak_bytes(Backend::cpu) - held);
  EXPECT_LE(output, m * (4 + 12 * 12) + 1024) << "bytes per particle " << output / (side * side * side);
}

// A restart's contact rows (contact_slots of a partner id and a spring per
// particle, 12 x 16 bytes here) go to the pending table, where they wait for
// the first list build, through slot-major blocks in backend memory a piece
// at a time (ParticleMover::arrive_from_host, arrival_piece: 1024 rows of the
// 4096), into a table reserved whole: so a restart peaks no higher than the
// run it continues (here both at the first build's peak, about 393 bytes per
// particle: the arrival holds about 370). Whole, the blocks would stand
// beside the table (522 bytes per particle); a table grown piece by piece
// would hold its old and new storage at each growth (471).
TEST(MemoryEstimate, RestartPeaksNoHigherThanTheRunItContinues) {
  const SceneSpec scene = lattice_scene(16, kFriction, 0.00198);  // each pressed 20 um into its neighbours
  const double n = double(scene.particles.size());
  backend_reset_peak(Backend::cpu);
  std::size_t before = backend_peak_bytes(Backend::cpu);
  Simulation first(scene, RunOptions{Backend::cpu});
  first.run(5);
  const double run_peak = double(backend_peak_bytes(Backend::cpu) - before) / n;
  const std::string path = (std::filesystem::path(::testing::TempDir()) / "memory_restart.h5").string();
  write_checkpoint(path, make_checkpoint(first.snapshot(), first.history(), first.walls(), 0, 1, first.insertion()));
  const RestartState state = restart_state(read_checkpoint(path));
  std::filesystem::remove(path);
  ASSERT_EQ(state.particles.history.slots, 12);
  backend_reset_peak(Backend::cpu);
  before = backend_peak_bytes(Backend::cpu);
  Simulation second(scene, RunOptions{Backend::cpu}, nullptr, state);
  second.run(5);
  const double restart_peak = double(backend_peak_bytes(Backend::cpu) - before) / n;
  // Within 2 bytes per particle (the run's own small arrays).
  EXPECT_LE(restart_peak, run_peak + 2) << "the run it continues: " << run_peak;
  EXPECT_GT(run_peak, 12 * (4 + 12));  // what the test is about: rows of that size
}

// A restart's rows wait as pair contacts only (the pending table: a partner
// id and a spring each, 16 bytes, and a row's offset), not as rows of
// contact_slots: with 24 slots a row would be 384 bytes per particle, more
// than the list's entries, their springs and the kept contacts of a build
// together, and the restart would peak above the run it continues (measured
// on the CPU before the pending table held pairs only: 564.3 bytes per
// particle against 401.4; now 401.5, the first build's). The lattice touches
// 5.81 a sphere. The estimate's
// restart (MemoryEstimate::restart_bytes: twelve pairs pending, each
// particle's origin and the kept contacts of the first build; by hand 196 +
// 4 + 100 less the forces, which wait on the host, 24, and the list and its
// entries, 64 and 156) is then below its build's peak (the kept contacts,
// 96, their offsets and the origins less the references and the forces).
TEST(MemoryEstimate, RestartRowsHoldOnlyTheirPairContacts) {
  SceneSpec scene = lattice_scene(32, kFriction, 0.00198);
  scene.domain_max = {0.05, 0.05, 0.05};
  scene.contact_slots = 24;
  const double n = double(scene.particles.size());
  backend_reset_peak(Backend::cpu);
  std::size_t before = backend_peak_bytes(Backend::cpu);
  Simulation first(scene, RunOptions{Backend::cpu});
  first.run(2);
  const double run_peak = double(backend_peak_bytes(Backend::cpu) - before) / n;
  const std::string path = (std::filesystem::path(::testing::TempDir()) / "memory_wide_rows.h5").string();
  write_checkpoint(path, make_checkpoint(first.snapshot(), first.history(), first.walls(), 0, 1, first.insertion()));
  const RestartState state = restart_state(read_checkpoint(path));
  std::filesystem::remove(path);
  ASSERT_EQ(state.particles.history.slots, 24);
  backend_reset_peak(Backend::cpu);
  before = backend_peak_bytes(Backend::cpu);
  Simulation second(scene, RunOptions{Backend::cpu}, nullptr, state);
  second.run(2);
  const double restart_peak = double(backend_peak_bytes(Backend::cpu) - before) / n;
  EXPECT_LE(restart_peak, run_peak + 2) << "the run it continues: " << run_peak;
  const MemoryEstimate m = estimate_memory(scene);
  EXPECT_DOUBLE_EQ(m.restart_bytes, 196 + 4 + 100 - 24 - 64 - 156);
  EXPECT_LT(m.restart_bytes, m.build_bytes);
}

}  // namespace
}  // namespace gs::test
