// The Verlet list's compact layout (neighbor/verlet_list.hpp). Its reference
// positions are kept in fp32 (distance_from_reference, read by ListWatch): a particle far from the origin,
// whose reference rounded towards the way it then moves, must still count as
// moved once it has truly moved half the skin, though the distance to its
// rounded reference is below that. Its offsets are unsigned 32-bit: a scan
// that wrapped past 2^32 is caught (OffsetsWrapped), not read as a short list.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "backend/cpu/cpu_exec.hpp"
#include "neighbor/cell_list.hpp"
#include "neighbor/verlet_list.hpp"

namespace gs::test {
namespace {

constexpr float kRadius = 0.0005f;
constexpr double kSkin = 1e-4;  // half the skin: 50 um

// Whether the list's check (ListWatch, with no margin and no move this step)
// finds one of the n particles more than half the skin from where the list
// saw it.
bool moved_half_skin(const VerletList& list, const std::vector<Vec3d>& x) {
  const std::vector<Vec3f> reference = list.reference.to_host();
  ListVerdict v;
  const ListWatch watch{reference.data(), list.box, 0.5 * list.skin, 0.0, &v};
  for (Index i = 0; i < Index(x.size()); ++i) watch(i, ParticleId(i), x[std::size_t(i)], 0.0);
  return v.stale_now != 0;
}

// Two spheres near x = 100 m (fp32 spacing there 7.6 um) and the list built
// over them; the first sits 0.45 of a spacing above 100 m, so its reference
// is rounded down by 3.4 um.
struct FarFromOrigin {
  CellList cells{Backend::cpu};
  DeviceArray<unsigned char> scratch{Backend::cpu};
  VerletList list{Backend::cpu};
  DeviceArray<Vec3d> position{Backend::cpu};
  DeviceArray<float> radius{Backend::cpu};
  DeviceArray<ParticleId> id{Backend::cpu};
  std::vector<Vec3d> start;

  FarFromOrigin() {
    const double spacing = std::ldexp(1.0, 6 - 23);  // fp32 ulp in [64, 128)
    start = {{100.0 + 0.45 * spacing, 100.5, 100.5}, {100.01, 100.5, 100.5}};
    position.from_host(start);
    radius.from_host(std::vector<float>{kRadius, kRadius});
    id.from_host(std::vector<ParticleId>{0, 1});
    const CellGrid grid = make_cell_grid({99.99, 100.49, 100.49}, {100.02, 100.51, 100.51}, 2 * kRadius + kSkin);
    build_cells<CpuExec>(cells, position.data(), id.data(), 2, grid, scratch);
    build_verlet_list<CpuExec>(list, cells, position.data(), radius.data(), id.data(), 2, 2, kSkin);
    set_list_references<CpuExec>(list, position.data());
  }
  // Whether the list is stale with the first sphere moved by dx along x.
  bool stale_after(double dx) {
    std::vector<Vec3d> moved = start;
    moved[0].x += dx;
    return moved_half_skin(list, moved);
  }
};

TEST(VerletReference, RoundingOfTheReferenceNeverHidesAMove) {
  FarFromOrigin f;
  const Vec3f r = f.list.reference.to_host()[0];
  const double rounded_by = f.start[0].x - double(r.x);
  ASSERT_GT(rounded_by, 3e-6);  // the set-up: the reference lies 3.4 um behind the sphere
  // Moved 52 um towards -x (more than half the skin): 48.6 um from the
  // rounded reference, which alone would not count as moved.
  const double dx = -(0.5 * kSkin + 2e-6);
  ASSERT_LT(std::fabs(f.start[0].x + dx - double(r.x)), 0.5 * kSkin);
  EXPECT_TRUE(f.stale_after(dx));
}

TEST(VerletReference, SmallMovesKeepTheList) {
  FarFromOrigin f;
  EXPECT_FALSE(f.stale_after(0.0));
  // The margin at 100 m is 2^-23 * 301 m = 36 um off the 50 um: a move of
  // 5 um either way keeps the list.
  EXPECT_FALSE(f.stale_after(5e-6));
  EXPECT_FALSE(f.stale_after(-5e-6));
  EXPECT_TRUE(f.stale_after(0.5 * kSkin));
}

// Near the origin the margin vanishes: a move of 0.49 of the skin keeps the
// list and 0.51 does not, as with fp64 references.
TEST(VerletReference, NearTheOriginTheTestIsHalfTheSkin) {
  CellList cells{Backend::cpu};
  DeviceArray<unsigned char> scratch{Backend::cpu};
  VerletList list{Backend::cpu};
  DeviceArray<Vec3d> position{Backend::cpu};
  DeviceArray<float> radius{Backend::cpu};
  DeviceArray<ParticleId> id{Backend::cpu};
  const std::vector<Vec3d> start = {{0.0, 0.0, 0.0}, {0.003, 0.001, 0.002}};
  position.from_host(start);
  radius.from_host(std::vector<float>{kRadius, kRadius});
  id.from_host(std::vector<ParticleId>{0, 1});
  const CellGrid grid = make_cell_grid({-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}, 2 * kRadius + kSkin);
  build_cells<CpuExec>(cells, position.data(), id.data(), 2, grid, scratch);
  build_verlet_list<CpuExec>(list, cells, position.data(), radius.data(), id.data(), 2, 2, kSkin);
  set_list_references<CpuExec>(list, position.data());
  for (const double fraction : {0.49, 0.51}) {
    std::vector<Vec3d> moved = start;
    moved[0].z -= fraction * kSkin;
    moved[1].y += 0.3 * kSkin;
    EXPECT_EQ(moved_half_skin(list, moved), fraction > 0.5) << fraction;
  }
}

// Offsets past 2^31 are valid (4e8 spheres of six neighbours: 2.4e9
// entries); a running sum past 2^32 wraps to a smaller value and is caught.
TEST(VerletOffsets, AWrappedScanIsCaught) {
  // Counts 2.5e9 and 1.5e9 (a list of 4e9 entries fits), then 0.5e9 more (4.5e9 does not).
  const ListOffset counts[] = {2500000000u, 1500000000u, 500000000u};
  std::vector<ListOffset> begin = {0};
  for (const ListOffset c : counts) begin.push_back(begin.back() + c);  // unsigned: wraps as the GPU's scan
  const OffsetsWrapped wrapped{begin.data()};
  EXPECT_FALSE(wrapped(0));
  EXPECT_FALSE(wrapped(1));  // 4e9 < 2^32
  EXPECT_TRUE(wrapped(2));   // 4.5e9 wrapped to 2e8
  // A zero count never looks like a wrap.
  const std::vector<ListOffset> flat = {0, 7, 7, 4000000000u, 4000000000u};
  for (Index i = 0; i + 1 < Index(flat.size()); ++i) EXPECT_FALSE(OffsetsWrapped{flat.data()}(i)) << i;
}

}  // namespace
}  // namespace gs::test
