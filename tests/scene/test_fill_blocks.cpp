// A random fill cut into blocks: every block made alone, in any order, on any
// thread or behind any window, is bit for bit the serial fill; blocks never
// overlap each other or the earlier sets; the count is shared by volume.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "scene/fill_blocks.hpp"
#include "scene/particle_sources.hpp"
#include "scene/scene_loader.hpp"

namespace gs {
namespace {

bool same_bits(const ParticleInit& a, const ParticleInit& b) {
  return a.id == b.id && a.material == b.material && a.marker == b.marker &&
         std::memcmp(&a.radius, &b.radius, sizeof(double)) == 0 &&
         std::memcmp(&a.position, &b.position, sizeof(Vec3d)) == 0 &&
         std::memcmp(&a.velocity, &b.velocity, sizeof(Vec3d)) == 0;
}

void expect_same(const std::vector<ParticleInit>& got, const std::vector<ParticleInit>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(same_bits(got[i], want[i])) << "particle " << i;
}

// 0.1 × 0.1 × 0.05 m with diameters up to 1 mm: 2 × 2 × 1 blocks of 40 diameters.
RandomFillSpec box_fill(std::size_t count) {
  RandomFillSpec s;
  s.region.min = Vec3d(0, 0, 0);
  s.region.max = Vec3d(0.1, 0.1, 0.05);
  s.count = count;
  s.size.kind = SizeSpec::Kind::uniform;
  s.size.radius_min = 0.0003;
  s.size.radius_max = 0.0005;
  s.seed = 11;
  s.tmpl.marker = 4;
  return s;
}

// A lattice through the middle of the box (obstacles across block faces), then the fill.
SceneSpec scene_with_fill(std::size_t count) {
  SceneSpec s;
  LatticeSpec l;
  l.radius = 0.001;
  l.spacing = 0.006;
  l.min = Vec3d(0.002, 0.002, 0.02);
  l.max = Vec3d(0.098, 0.098, 0.03);
  const std::size_t sites = lattice_count(l);
  s.lattices.push_back({l, 0, sites});
  s.fills.push_back(make_fill_source(box_fill(count), sites));
  return s;
}

bool in_box(const Vec3d& x, const Vec3d& lo, const Vec3d& hi) {
  return x.x >= lo.x && x.y >= lo.y && x.z >= lo.z && x.x <= hi.x && x.y <= hi.y && x.z <= hi.z;
}

TEST(FillBlocks, ThreadsWindowsAndBlockOrderGiveTheSerialFill) {
  const SceneSpec s = scene_with_fill(40000);
  const RandomFillSource& fill = s.fills.front();
  ASSERT_EQ(fill.blocks.count(), 4u);
  // Serial: the lattice, then every block in order around it.
  std::vector<ParticleInit> serial;
  generate_lattice(s.lattices.front().spec, serial);
  generate_random_fill(fill.spec, serial);
  const std::vector<ParticleInit> all = all_particles(s);  // every thread, blocks in chunks
  expect_same(all, serial);
  for (std::size_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i].id, i);
  // Blocks made alone and last first, around the obstacles near each.
  const ParticleStream stream(s);
  std::vector<ParticleInit> backwards;
  for (std::size_t b = fill.blocks.count(); b-- > 0;) {
    std::vector<ParticleInit> block;
    generate_fill_block(fill, b, [&](const Vec3d& lo, const Vec3d& hi, const SphereVisitor& visit) {
      stream.for_each_near(fill.first_id, lo, hi, visit);
    }, block);
    backwards.insert(backwards.begin(), block.begin(), block.end());
  }
  expect_same(backwards, std::vector<ParticleInit>(serial.begin() + std::ptrdiff_t(fill.first_id), serial.end()));
  // A rank's window: only the blocks meeting it are made, and the selection is the same.
  const Vec3d lo(0.06, -1, -1), hi(1, 1, 1);
  const auto keep = [&](const Vec3d& x) { return in_box(x, lo, hi); };
  std::vector<ParticleInit> want, got;
  for (const ParticleInit& p : all)
    if (keep(p.position)) want.push_back(p);
  for_each_selected_block(
      s, keep, KeepWindow{lo, hi}, std::size_t(1) << 22, [&](std::size_t n) { got.resize(n); },
      [&](std::size_t k, const ParticleInit& p) { got[k] = p; }, [](std::size_t, std::size_t) {});
  expect_same(got, want);
}

TEST(FillBlocks, NoOverlapAcrossBlocksOrWithEarlierSetsAndAllInside) {
  const SceneSpec s = scene_with_fill(60000);
  const std::vector<ParticleInit> all = all_particles(s);
  std::size_t a = 0, b = 0;
  EXPECT_FALSE(find_overlap(all, a, b, 0.0)) << a << " overlaps " << b;
  const RandomFillSpec& spec = s.fills.front().spec;
  for (std::size_t i = s.fills.front().first_id; i < all.size(); ++i)
    ASSERT_TRUE(admits(spec.region, all[i].position, all[i].radius)) << "particle " << i;
}

// A cylinder cut 3 × 3 across its axis: each block's share of the count is
// its share of the area where a largest sphere's centre fits (the disk of
// radius R - r_max within the block's face-shrunk square), measured here on
// a fine grid of its own.
TEST(FillBlocks, CountIsSharedByUsableVolume) {
  RandomFillSpec s;
  s.region.kind = FillRegion::Kind::cylinder;
  s.region.base = Vec3d(0, 0, 0);
  s.region.axis = Vec3d(0, 0, 1);
  s.region.radius = 0.06;
  s.region.length = 0.01;
  s.size.radius_min = s.size.radius_max = 0.0005;  // blocks of 0.04 m: 3 × 3 × 1
  s.count = 50000;
  const RandomFillSource f = make_fill_source(s, 0);
  ASSERT_EQ(f.blocks.n[0], 3);
  ASSERT_EQ(f.blocks.n[1], 3);
  ASSERT_EQ(f.blocks.n[2], 1);
  ASSERT_EQ(f.blocks.start.back(), s.count);
  const double r = 0.0005, R = s.region.radius - r;
  std::vector<double> area(9, 0.0);
  constexpr int k = 1200;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      const double x = -0.06 + 0.12 * (i + 0.5) / k, y = -0.06 + 0.12 * (j + 0.5) / k;
      if (x * x + y * y > R * R) continue;
      const int bx = x < -0.02 ? 0 : x < 0.02 ? 1 : 2, by = y < -0.02 ? 0 : y < 0.02 ? 1 : 2;
      // Inner faces keep centres a radius away.
      if ((bx > 0 && x < (bx == 1 ? -0.02 : 0.02) + r) || (bx < 2 && x > (bx == 1 ? 0.02 : -0.02) - r)) continue;
      if ((by > 0 && y < (by == 1 ? -0.02 : 0.02) + r) || (by < 2 && y > (by == 1 ? 0.02 : -0.02) - r)) continue;
      area[std::size_t(by * 3 + bx)] += 1;
    }
  double total = 0;
  for (double a : area) total += a;
  for (std::size_t b = 0; b < 9; ++b) {
    const double share = double(f.blocks.start[b + 1] - f.blocks.start[b]) / double(s.count);
    EXPECT_NEAR(share, area[b] / total, 0.02 * area[b] / total + 1e-4) << "block " << b;
  }
}

TEST(FillBlocks, TooFullBlockNamesTheFill) {
  RandomFillSpec s = box_fill(0);
  s.region.max = Vec3d(0.01, 0.01, 0.01);  // one block
  s.size.kind = SizeSpec::Kind::fixed;
  s.size.radius_min = s.size.radius_max = 0.0005;
  // Solid fraction 0.5: allowed by the up-front check, beyond what random addition reaches.
  s.count = std::size_t(0.5 * 1e-6 / (4.0 / 3.0 * M_PI * 1.25e-10));
  s.max_attempts = 50;
  const RandomFillSource f = make_fill_source(s, 7);
  std::vector<ParticleInit> out;
  try {
    generate_fill_block(f, 0, [](const Vec3d&, const Vec3d&, const SphereVisitor&) {}, out);
    FAIL() << "a block at solid fraction 0.5 was filled";
  } catch (const GenerateError& e) {
    EXPECT_EQ(e.set_first, 7u);
    EXPECT_NE(std::string(e.what()).find("too full"), std::string::npos) << e.what();
  }
}

// The shipped scenes with a fill still get every particle they ask for (the
// loader generates them all for its checks), with consecutive ids and no overlap.
TEST(FillBlocks, ShippedFillScenesGetTheirCount) {
  const std::string here = __FILE__;
  const std::string root = here.substr(0, here.rfind("tests/scene/"));
  for (const auto& [path, count] : {std::pair<std::string, std::size_t>{"cases/demo/settle.yaml", 2000},
                                    {"cases/mixer/case_a.yaml", 7680}, {"cases/mixer/case_b.yaml", 76800}}) {
    if (!std::ifstream(root + path)) GTEST_SKIP() << "no " << root + path;
    const SceneSpec s = load_scene(root + path);
    const std::vector<ParticleInit> all = all_particles(s);
    ASSERT_EQ(all.size(), count) << path;
    for (std::size_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i].id, i) << path;
    std::size_t a = 0, b = 0;
    EXPECT_FALSE(find_overlap(all, a, b, 0.0)) << path << ": " << a << " overlaps " << b;
  }
}

}  // namespace
}  // namespace gs
