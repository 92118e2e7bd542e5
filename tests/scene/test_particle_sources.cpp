// Particles generated where they are needed: any share of the id sequence,
// on any number of threads, is bit for bit the serial generation's.
#include <gtest/gtest.h>

#include <cstring>

#include "scene/particle_sources.hpp"

namespace gs {
namespace {

bool same_bits(const ParticleInit& a, const ParticleInit& b) {
  return a.id == b.id && a.material == b.material && a.marker == b.marker &&
         std::memcmp(&a.radius, &b.radius, sizeof(double)) == 0 &&
         std::memcmp(&a.position, &b.position, sizeof(Vec3d)) == 0 &&
         std::memcmp(&a.velocity, &b.velocity, sizeof(Vec3d)) == 0 &&
         std::memcmp(&a.angular_velocity, &b.angular_velocity, sizeof(Vec3d)) == 0;
}

void expect_same(const std::vector<ParticleInit>& got, const std::vector<ParticleInit>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(same_bits(got[i], want[i])) << "particle " << i;
}

ParticleInit listed(ParticleId id, double z) {
  ParticleInit p;
  p.id = id;
  p.radius = 0.0004;
  p.position = Vec3d(-0.01, 0.0, z);
  p.marker = 3;
  return p;
}

LatticeSpec lattice() {
  LatticeSpec l;
  l.tmpl.material = 1;
  l.tmpl.velocity = Vec3d(0.1, 0, -0.3);
  l.tmpl.marker = 5;
  l.radius = 0.0005;
  l.min = Vec3d(0.0011, -0.0203, 0.0007);
  l.spacing = 0.0011;
  // 50 x 41 x 37 sites: more than one chunk of the parallel generation.
  l.max = l.min + Vec3d(49.5, 40.5, 36.5) * l.spacing;
  return l;
}

// Ten listed particles, the lattice, one more listed particle.
SceneSpec scene() {
  SceneSpec s;
  for (ParticleId id = 0; id < 10; ++id) s.particles.push_back(listed(id, 0.001 * id));
  s.lattices.push_back({lattice(), 10, 50u * 41u * 37u});
  s.particles.push_back(listed(ParticleId(10 + s.lattices[0].count), 0.5));
  return s;
}

// The serial generator as it was: sites x fastest, position min + spacing (i, j, k).
std::vector<ParticleInit> serial(const SceneSpec& s) {
  std::vector<ParticleInit> out(s.particles.begin(), s.particles.begin() + 10);
  const LatticeSpec l = lattice();
  for (int k = 0; k < 37; ++k)
    for (int j = 0; j < 41; ++j)
      for (int i = 0; i < 50; ++i) {
        ParticleInit p;
        p.id = ParticleId(out.size());
        p.material = l.tmpl.material;
        p.radius = l.radius;
        p.position = l.min + l.spacing * Vec3d(double(i), double(j), double(k));
        p.velocity = l.tmpl.velocity;
        p.marker = l.tmpl.marker;
        out.push_back(p);
      }
  out.push_back(s.particles.back());
  return out;
}

TEST(ParticleSources, CountAndRadiiWithoutGenerating) {
  const SceneSpec s = scene();
  EXPECT_EQ(particle_count(s), 11u + 50u * 41u * 37u);
  EXPECT_EQ(largest_radius(s), 0.0005);
  EXPECT_EQ(smallest_radius(s), 0.0004);
}

TEST(ParticleSources, EveryRankCountsShareIsTheSerialGeneration) {
  const SceneSpec s = scene();
  const std::vector<ParticleInit> want = serial(s);
  const ParticleStream stream(s);
  ASSERT_EQ(stream.count(), want.size());
  for (std::size_t ranks = 1; ranks <= 4; ++ranks) {
    std::vector<ParticleInit> joined;
    for (std::size_t k = 0; k < ranks; ++k) {
      std::vector<ParticleInit> share;
      stream.generate(want.size() * k / ranks, want.size() * (k + 1) / ranks, share);
      joined.insert(joined.end(), share.begin(), share.end());
    }
    expect_same(joined, want);
  }
}

TEST(ParticleSources, SelectedParticlesAreTheOwnedOnesInIdOrder) {
  const SceneSpec s = scene();
  const std::vector<ParticleInit> want = serial(s);
  expect_same(all_particles(s), want);
  // Slabs along z as ranks: each keeps exactly its own, in id order.
  const double cut[] = {-1, 0.01, 0.02, 0.03, 1};
  std::size_t total = 0;
  for (int r = 0; r < 4; ++r) {
    auto mine = [&](const Vec3d& x) { return x.z >= cut[r] && x.z < cut[r + 1]; };
    std::vector<ParticleInit> owned;
    for (const ParticleInit& p : want)
      if (mine(p.position)) owned.push_back(p);
    const std::vector<ParticleInit> got = select_particles(s, mine);
    EXPECT_LT(got.size(), want.size());
    expect_same(got, owned);
    total += got.size();
  }
  EXPECT_EQ(total, want.size());
}

TEST(ParticleSources, PositionBlocksAndFirstMatch) {
  const SceneSpec s = scene();
  const std::vector<ParticleInit> want = serial(s);
  std::vector<Vec3d> x;
  for_each_position_block(s, 5, want.size(), [&](const std::vector<Vec3d>& b) { x.insert(x.end(), b.begin(), b.end()); });
  ASSERT_EQ(x.size(), want.size() - 5);
  for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(std::memcmp(&x[i], &want[i + 5].position, sizeof(Vec3d)), 0);
  const double z = want[70001].position.z;
  auto high = [z](const ParticleInit& p) { return p.position.z >= z && p.material == 1; };
  std::size_t first = 0;
  while (!high(want[first])) ++first;
  EXPECT_EQ(find_first(s, 0, want.size(), high), first);
  EXPECT_EQ(find_first(s, 0, first, high), first);  // none before it: `last`
}

}  // namespace
}  // namespace gs
