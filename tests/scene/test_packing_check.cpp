// The packing checks split over ranks (scene/packing_check.hpp): shares of the
// ids (the fit) or of space (the overlaps) find, between them, the offence the
// check over every particle finds, which a plain search over all particles
// confirms; and the random-fill blocks a rank's set-up passes read are made
// once (scene/kept_fill_blocks.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>

#include "scene/fill_blocks.hpp"
#include "scene/kept_fill_blocks.hpp"
#include "scene/packing_check.hpp"
#include "scene/particle_sources.hpp"

namespace gs {
namespace {

constexpr double kRadius = 0.0002;

// 20000 spheres in a 4 x 4 x 8 cm box (four blocks), one set at line 3.
SceneSpec fill_scene() {
  SceneSpec s;
  s.path = "fill.yaml";
  s.domain_min = Vec3d(-0.01, -0.01, -0.01);
  s.domain_max = Vec3d(0.05, 0.05, 0.09);
  RandomFillSpec f;
  f.region.kind = FillRegion::Kind::box;
  f.region.min = Vec3d(0, 0, 0);
  f.region.max = Vec3d(0.04, 0.04, 0.08);
  f.count = 20000;
  f.size.kind = SizeSpec::Kind::fixed;
  f.size.radius_min = f.size.radius_max = kRadius;
  f.seed = 5;
  s.fills.push_back(make_fill_source(f, 0));
  s.set_origins.push_back({0, 3, "particles[0].random_fill"});
  return s;
}

bool overlap(const ParticleInit& a, const ParticleInit& b) {
  const double reach = (a.radius + b.radius) * (1 - kTouchTolerance);
  return norm2(a.position - b.position) < reach * reach;
}

// The first particle overlapping one of a lower id, by a sweep along x over
// every pair within reach: independent of the checks' grids and windows.
std::size_t first_overlap_plainly(const std::vector<ParticleInit>& ps, double reach) {
  std::vector<std::size_t> by_x(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) { return ps[a].position.x < ps[b].position.x; });
  std::size_t first = ps.size();
  for (std::size_t u = 0; u < by_x.size(); ++u)
    for (std::size_t v = u + 1; v < by_x.size() && ps[by_x[v]].position.x - ps[by_x[u]].position.x < reach; ++v)
      if (overlap(ps[by_x[u]], ps[by_x[v]])) first = std::min(first, std::size_t(std::max(ps[by_x[u]].id, ps[by_x[v]].id)));
  return first;
}

TEST(PackingCheck, FitSharedOverIdSharesFindsTheFirstMisfit) {
  SceneSpec s = fill_scene();
  s.domain_max.z = 0.07;  // the fill's top centimetre sticks out
  const std::size_t n = particle_count(s);
  std::size_t plain = n;
  for (const ParticleInit& p : all_particles(s))
    if (p.position.z + p.radius * (1 - kTouchTolerance) > s.domain_max.z) plain = std::min(plain, std::size_t(p.id));
  ASSERT_LT(plain, n);
  EXPECT_EQ(first_misfit(s, 0, n), plain);
  for (std::size_t ranks : {2u, 3u, 5u}) {
    std::size_t first = n;
    for (std::size_t k = 0; k < ranks; ++k) {
      const std::size_t a = n * k / ranks, b = n * (k + 1) / ranks, bad = first_misfit(s, a, b);
      if (bad < b) first = std::min(first, bad);
    }
    EXPECT_EQ(first, plain) << ranks << " shares";
  }
  try {
    report_misfit(s, plain);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fill.yaml:3: particles[0].random_fill: particle " + std::to_string(plain), 0), 0u)
        << e.what();
  }
}

// A listed sphere (id 20000, a set at line 9) overlaps exactly one fill
// particle `a`; the plane between them splits space in two shares, so the
// share that owns the sphere finds its partner only in its margin.
TEST(PackingCheck, OverlapAcrossSharesIsFoundByTheShareOfTheHigherId) {
  SceneSpec s = fill_scene();
  const std::vector<ParticleInit> fill = all_particles(s);
  ParticleInit b;
  b.id = ParticleId(fill.size());
  b.radius = kRadius;
  std::size_t a = fill.size();
  for (std::size_t i = fill.size() / 2; i < fill.size() && a == fill.size(); ++i) {
    b.position = fill[i].position + Vec3d(1.5 * kRadius, 0, 0);
    std::size_t touching = 0;
    for (const ParticleInit& p : fill) touching += overlap(p, b) ? 1 : 0;
    if (touching == 1) a = i;
  }
  ASSERT_LT(a, fill.size());
  s.particles.push_back(b);
  s.set_origins.push_back({b.id, 9, "particles[1].list[0]"});
  std::vector<ParticleInit> all = fill;
  all.push_back(b);
  ASSERT_EQ(first_overlap_plainly(all, 2 * kRadius), std::size_t(b.id));
  EXPECT_EQ(first_overlapping(s, every_particle()), std::size_t(b.id));

  const double plane = fill[a].position.x + 0.75 * kRadius, inf = std::numeric_limits<double>::infinity();
  const ParticleShare below{[plane](const Vec3d& x) { return x.x < plane; }, {Vec3d(-inf, -inf, -inf), Vec3d(plane, inf, inf)}};
  const ParticleShare above{[plane](const Vec3d& x) { return x.x >= plane; }, {Vec3d(plane, -inf, -inf), Vec3d(inf, inf, inf)}};
  const std::size_t n = particle_count(s);
  EXPECT_EQ(first_overlapping(s, below), n);
  EXPECT_EQ(first_overlapping(s, above), std::size_t(b.id));
  try {
    report_overlap(s, b.id);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    const std::string want = "fill.yaml:9: particles[1].list[0]: particle " + std::to_string(b.id);
    EXPECT_EQ(std::string(e.what()).rfind(want, 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("overlaps particle " + std::to_string(a) + " at"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(particles[0].random_fill, line 3)"), std::string::npos) << e.what();
  }
}

bool same_bits(const std::vector<ParticleInit>& a, const std::vector<ParticleInit>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].id != b[i].id || std::memcmp(&a[i].position, &b[i].position, sizeof(Vec3d)) != 0 ||
        std::memcmp(&a[i].radius, &b[i].radius, sizeof(double)) != 0)
      return false;
  return true;
}

// The passes of a rank's set-up (fit check, split, overlap check, upload's
// count and write) read each block once made, with the bits of a scene that
// keeps none.
TEST(KeptFillBlocks, EachBlockIsMadeOnceAcrossPasses) {
  const SceneSpec plain = fill_scene();
  SceneSpec s = plain;
  s.kept_blocks = std::make_shared<KeptFillBlocks>(std::size_t(1) << 30);
  const std::size_t n = particle_count(s), blocks = s.fills[0].blocks.count();
  ASSERT_GE(blocks, 4u);
  EXPECT_EQ(first_misfit(s, 0, n), n);
  EXPECT_EQ(s.kept_blocks->made(), blocks);
  EXPECT_EQ(s.kept_blocks->kept_bytes(), n * sizeof(ParticleInit));
  const auto low = [](const Vec3d& x) { return x.z < 0.03; };
  const KeepWindow window{Vec3d(-1, -1, -1), Vec3d(1, 1, 0.03)};
  const std::vector<ParticleInit> mine = select_particles(s, low, window);
  std::vector<Vec3d> x;
  for_each_position_block(s, 0, n, [&](const std::vector<Vec3d>& b) { x.insert(x.end(), b.begin(), b.end()); });
  EXPECT_EQ(s.kept_blocks->made(), blocks);
  EXPECT_TRUE(same_bits(mine, select_particles(plain, low, window)));
  EXPECT_EQ(x.size(), n);

  // A window keeps the blocks that meet it; one outside is made again when needed.
  s.kept_blocks->keep_only(window.lo, window.hi);
  const std::size_t kept = s.kept_blocks->kept_bytes();
  EXPECT_GT(kept, 0u);
  EXPECT_LT(kept, n * sizeof(ParticleInit));
  EXPECT_TRUE(same_bits(all_particles(s), all_particles(plain)));
  EXPECT_GT(s.kept_blocks->made(), blocks);
  EXPECT_EQ(s.kept_blocks->kept_bytes(), kept);
}

TEST(KeptFillBlocks, NoBudgetKeepsNothing) {
  SceneSpec s = fill_scene();
  s.kept_blocks = std::make_shared<KeptFillBlocks>(0);
  const std::size_t n = particle_count(s);
  first_misfit(s, 0, n);
  const std::size_t once = s.kept_blocks->made();
  first_misfit(s, 0, n);
  EXPECT_EQ(s.kept_blocks->kept_bytes(), 0u);
  EXPECT_GT(s.kept_blocks->made(), once);
}

}  // namespace
}  // namespace gs
