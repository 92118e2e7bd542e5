#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "scene/generators.hpp"

namespace gs {
namespace {

// Brute force, independent of the grid the generators use.
bool any_overlap(const std::vector<ParticleInit>& ps, std::size_t& a, std::size_t& b) {
  for (a = 0; a < ps.size(); ++a)
    for (b = a + 1; b < ps.size(); ++b) {
      const double reach = ps[a].radius + ps[b].radius;
      if (norm2(ps[a].position - ps[b].position) < reach * reach) return true;
    }
  return false;
}

RandomFillSpec box_fill(std::size_t count, double r_min, double r_max, std::uint64_t seed) {
  RandomFillSpec s;
  s.region.kind = FillRegion::Kind::box;
  s.region.min = Vec3d(0, 0, 0);
  s.region.max = Vec3d(0.04, 0.04, 0.08);
  s.count = count;
  s.size.kind = r_min == r_max ? SizeSpec::Kind::fixed : SizeSpec::Kind::uniform;
  s.size.radius_min = r_min;
  s.size.radius_max = r_max;
  s.seed = seed;
  s.tmpl.material = 2;
  s.tmpl.marker = 9;
  s.tmpl.velocity = Vec3d(0, 0, -1);
  return s;
}

TEST(Lattice, CountIsExactAndSitesAreOnTheLattice) {
  LatticeSpec l;
  l.radius = 0.001;
  l.spacing = 0.003;
  l.min = Vec3d(0.01, 0.01, 0.01);
  l.max = Vec3d(0.019, 0.029, 0.039);  // 4 x 7 x 10 sites; 0.019 = 0.01 + 3 * 0.003 sits exactly on the edge
  EXPECT_EQ(lattice_count(l), 280u);
  std::vector<ParticleInit> out(5);  // earlier particles: ids continue after them
  generate_lattice(l, out);
  ASSERT_EQ(out.size(), 285u);
  for (std::size_t i = 5; i < out.size(); ++i) {
    EXPECT_EQ(out[i].id, i);
    EXPECT_EQ(out[i].radius, 0.001);
    const Vec3d p = out[i].position;
    EXPECT_GE(p.x, l.min.x);
    EXPECT_LE(p.z, l.max.z + 1e-12);
    const double k = (p.y - l.min.y) / l.spacing;
    EXPECT_NEAR(k, std::round(k), 1e-9);
  }
  EXPECT_EQ(lattice_sites(0, 1, 0.25), 5u);
  EXPECT_EQ(lattice_sites(1, 0, 0.25), 0u);
}

// Counts beyond the particle ids are refused, not wrapped: a max of 1e20 m
// used to give one layer of 16 spheres.
TEST(Lattice, OverflowingCountsAreRefused) {
  EXPECT_THROW(lattice_sites(0, 1e20, 0.003), GenerateError);
  LatticeSpec l;
  l.radius = 0.001;
  l.spacing = 0.003;
  l.min = Vec3d(0, 0, 0);
  l.max = Vec3d(1e20, 0.01, 0.01);
  EXPECT_THROW(lattice_count(l), GenerateError);
  // Each axis fits, the product does not: 1e4 sites per axis is 1e12 sites.
  l.max = Vec3d(30, 30, 30);
  EXPECT_THROW(lattice_count(l), GenerateError);
  std::vector<ParticleInit> out;
  EXPECT_THROW(generate_lattice(l, out), GenerateError);
  EXPECT_TRUE(out.empty());
}

TEST(RandomFill, NoOverlapsAndInsideRegionWithOneToFiveSizes) {
  std::vector<ParticleInit> out;
  generate_random_fill(box_fill(2000, 0.0002, 0.001, 7), out);
  ASSERT_EQ(out.size(), 2000u);
  double smallest = 1, largest = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const ParticleInit& p = out[i];
    EXPECT_EQ(p.id, i);
    EXPECT_EQ(p.material, 2);
    EXPECT_EQ(p.marker, 9);
    EXPECT_EQ(p.velocity.z, -1);
    const double r = p.radius;
    smallest = std::min(smallest, r);
    largest = std::max(largest, r);
    EXPECT_TRUE(p.position.x >= r && p.position.y >= r && p.position.z >= r) << i;
    EXPECT_TRUE(p.position.x <= 0.04 - r && p.position.y <= 0.04 - r && p.position.z <= 0.08 - r) << i;
  }
  EXPECT_GT(largest / smallest, 4.5);  // the size ratio really is ~1:5
  std::size_t a = 0, b = 0;
  EXPECT_FALSE(any_overlap(out, a, b)) << a << " overlaps " << b;
  EXPECT_FALSE(find_overlap(out, a, b));
}

TEST(RandomFill, DenseMonodisperseFillHasNoOverlaps) {
  // Solid fraction 0.25: deep into the regime where the taken-cell bitmap matters.
  RandomFillSpec s = box_fill(3000, 0.001, 0.001, 3);
  s.region.max = Vec3d(0.04, 0.04, 0.04 * 3000 * (4.0 / 3.0 * M_PI * 1e-9) / 0.25 / 0.0016 / 0.04);
  std::vector<ParticleInit> out;
  generate_random_fill(s, out);
  std::size_t a = 0, b = 0;
  EXPECT_FALSE(any_overlap(out, a, b)) << a << " overlaps " << b;
  // Skipping taken space must not skew the fill: as many centres in each half.
  const double mid = 0.5 * s.region.max.z;
  const auto low = std::count_if(out.begin(), out.end(), [&](const ParticleInit& p) { return p.position.z < mid; });
  EXPECT_NEAR(double(low) / double(out.size()), 0.5, 0.04);
}

TEST(RandomFill, CylinderRegionKeepsParticlesInside) {
  RandomFillSpec s = box_fill(1500, 0.0005, 0.001, 11);
  s.region.kind = FillRegion::Kind::cylinder;
  s.region.base = Vec3d(0.1, 0.2, 0.3);
  s.region.axis = Vec3d(0, 0.6, 0.8);
  s.region.radius = 0.02;
  s.region.length = 0.05;
  std::vector<ParticleInit> out;
  generate_random_fill(s, out);
  for (const ParticleInit& p : out) {
    const Vec3d d = p.position - s.region.base;
    const double along = dot(d, s.region.axis);
    EXPECT_GE(along, p.radius - 1e-12);
    EXPECT_LE(along, s.region.length - p.radius + 1e-12);
    EXPECT_LE(norm(d - along * s.region.axis), s.region.radius - p.radius + 1e-12);
  }
  std::size_t a = 0, b = 0;
  EXPECT_FALSE(any_overlap(out, a, b)) << a << " overlaps " << b;
}

TEST(RandomFill, SameSeedSameFillOtherSeedOtherFill) {
  std::vector<ParticleInit> one, two, three;
  generate_random_fill(box_fill(500, 0.0005, 0.001, 42), one);
  generate_random_fill(box_fill(500, 0.0005, 0.001, 42), two);
  generate_random_fill(box_fill(500, 0.0005, 0.001, 43), three);
  bool all_same = true, any_differs = false;
  for (std::size_t i = 0; i < one.size(); ++i) {
    all_same = all_same && norm2(one[i].position - two[i].position) == 0 && one[i].radius == two[i].radius;
    any_differs = any_differs || norm2(one[i].position - three[i].position) > 0;
  }
  EXPECT_TRUE(all_same);
  EXPECT_TRUE(any_differs);
}

TEST(RandomFill, AvoidsParticlesOfEarlierSets) {
  LatticeSpec l;
  l.radius = 0.002;
  l.spacing = 0.008;
  l.min = Vec3d(0.004, 0.004, 0.004);
  l.max = Vec3d(0.036, 0.036, 0.076);
  std::vector<ParticleInit> out;
  generate_lattice(l, out);
  const std::size_t lattice = out.size();
  generate_random_fill(box_fill(1500, 0.0005, 0.001, 5), out);
  EXPECT_EQ(out.size(), lattice + 1500);
  EXPECT_EQ(out.back().id, out.size() - 1);
  std::size_t a = 0, b = 0;
  EXPECT_FALSE(any_overlap(out, a, b)) << a << " overlaps " << b;
}

TEST(RandomFill, DiameterDistributionFractionsByCount) {
  SizeSpec size;
  size.kind = SizeSpec::Kind::classes;
  size.classes = {{0.001, 0.2}, {0.002, 0.5}, {0.0005, 0.3}};
  const std::vector<double> radii = random_fill_radii(size, 2000, 1);
  std::map<double, int> count;
  for (double r : radii) ++count[r];
  EXPECT_EQ(count[0.0005], 400);
  EXPECT_EQ(count[0.001], 1000);
  EXPECT_EQ(count[0.00025], 600);
  EXPECT_TRUE(std::is_sorted(radii.rbegin(), radii.rend()));  // largest first

  size.classes = {{0.001, 1.0 / 3}, {0.002, 1.0 / 3}, {0.003, 1.0 / 3}};
  std::map<double, int> thirds;
  for (double r : random_fill_radii(size, 1000, 1)) ++thirds[r];
  for (const auto& [r, n] : thirds) EXPECT_NEAR(n, 333.3, 1.0) << r;

  // The same through a whole fill, with a 1:4 size range.
  RandomFillSpec s = box_fill(2000, 0, 0, 9);
  s.size = size;
  s.size.classes = {{0.0005, 0.7}, {0.002, 0.3}};
  std::vector<ParticleInit> out;
  generate_random_fill(s, out);
  const auto small = std::count_if(out.begin(), out.end(), [](const ParticleInit& p) { return p.radius < 0.0005; });
  EXPECT_NEAR(double(small) / 2000.0, 0.7, 0.001);
}

TEST(RandomFill, TooFullRegionIsReported) {
  std::vector<ParticleInit> out;
  // 2000 spheres of d = 2 mm need 8.4 cm^3; 1 cm^3 is far too small.
  RandomFillSpec s = box_fill(2000, 0.001, 0.001, 1);
  s.region.max = Vec3d(0.01, 0.01, 0.01);
  try {
    generate_random_fill(s, out);
    FAIL() << "no error";
  } catch (const GenerateError& e) {
    EXPECT_NE(std::string(e.what()).find("too full"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bigger region"), std::string::npos) << e.what();
  }
  // Below random close packing but beyond what random addition reaches (~0.38).
  s.region.max = Vec3d(0.02, 0.02, 0.02 * 2000 * (4.0 / 3.0 * M_PI * 1e-9) / 0.5 / 0.0004 / 0.02);
  s.max_attempts = 200;
  EXPECT_THROW(generate_random_fill(s, out), GenerateError);
}

TEST(FindOverlap, FindsAPlantedOverlap) {
  std::vector<ParticleInit> out;
  generate_random_fill(box_fill(1000, 0.0005, 0.001, 2), out);
  std::size_t a = 0, b = 0;
  ASSERT_FALSE(find_overlap(out, a, b));
  ParticleInit extra = out[123];
  extra.position.x += 0.5 * extra.radius;
  out.push_back(extra);
  ASSERT_TRUE(find_overlap(out, a, b));
  EXPECT_EQ(std::min(a, b), 123u);
  EXPECT_EQ(std::max(a, b), out.size() - 1);
}

}  // namespace
}  // namespace gs
