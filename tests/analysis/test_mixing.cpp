// The mixing analysis (src/analysis/mixing.*, docs/MIXING.md): sample
// placement, the per-sample tallies against a brute-force count, the Lacey
// index and RSD of segregated and random beds, the CSV log and the scene keys.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "analysis/mixing.hpp"
#include "analysis/mixing_log.hpp"
#include "engine/simulation.hpp"
#include "scene/scene_loader.hpp"

namespace gs {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Rings at 15, 25, 35, 45 mm (annulus 10..50 mm, 4 rings), 4 mm samples 20 mm tall from z = 5 mm.
SampleSpec annulus_samples() {
  SampleSpec s;
  s.center_x = 0.2;
  s.center_y = -0.1;
  s.ring_radii = ring_radii_in_annulus(0.010, 0.050, 4);
  s.spacing = 0.010;
  s.radius = 0.004;
  s.height = 0.020;
  s.bottom = 0.005;
  return s;
}

// `n` particles at uniformly random points of the cylinder around the samples'
// axis, radius `bed_radius`, z in [0, 0.03]; masses vary by +-50 %; marker 0.
ParticleSnapshot random_bed(const SampleSpec& axis, double bed_radius, std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  ParticleSnapshot snap;
  snap.time = 1.5;
  snap.step = 42;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = bed_radius * std::sqrt(u(rng)), angle = 2 * kPi * u(rng);
    snap.id.push_back(ParticleId(i));
    snap.position.emplace_back(axis.center_x + r * std::cos(angle), axis.center_y + r * std::sin(angle), 0.03 * u(rng));
    snap.radius.push_back(0.0005f);
    snap.mass.push_back(float(1e-6 * (0.5 + u(rng))));
    snap.marker.push_back(0);
  }
  return snap;
}

bool inside(const SampleSpec& s, const SampleSite& site, const Vec3d& p) {
  const double dx = p.x - site.x, dy = p.y - site.y;
  return dx * dx + dy * dy <= s.radius * s.radius && p.z >= s.bottom && p.z <= s.bottom + s.height;
}

TEST(MixingSamples, EquidistantOnRingsCountProportionalToRadiusInsideAnnulus) {
  const SampleSpec spec = annulus_samples();
  ASSERT_EQ(sample_layout_problem(spec), "");
  const SampleLayout layout(spec);
  ASSERT_EQ(layout.ring_count(), 4);
  const auto& sites = layout.sites();
  std::size_t first = 0;
  for (int k = 0; k < layout.ring_count(); ++k) {
    const double r = spec.ring_radii[std::size_t(k)];
    EXPECT_NEAR(r, 0.015 + 0.010 * k, 1e-15);
    const int n = layout.samples_on_ring(k);
    // Count proportional to the circumference: n is 2 pi r / spacing rounded.
    EXPECT_LE(std::abs(n - 2 * kPi * r / spec.spacing), 0.5) << "ring " << k;
    const double chord = 2 * r * std::sin(kPi / n);
    for (int j = 0; j < n; ++j) {
      const SampleSite& a = sites[first + std::size_t(j)];
      const SampleSite& b = sites[first + std::size_t((j + 1) % n)];
      EXPECT_EQ(a.ring, k);
      const double rho = std::hypot(a.x - spec.center_x, a.y - spec.center_y);
      EXPECT_NEAR(rho, r, 1e-12);
      EXPECT_NEAR(std::hypot(b.x - a.x, b.y - a.y), chord, 1e-12) << "not equidistant on ring " << k;
      EXPECT_GE(rho - spec.radius, 0.010 - 1e-12);  // the whole cylinder lies in the annulus
      EXPECT_LE(rho + spec.radius, 0.050 + 1e-12);
    }
    first += std::size_t(n);
  }
  EXPECT_EQ(first, sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i)  // no two samples overlap
    for (std::size_t j = i + 1; j < sites.size(); ++j)
      EXPECT_GE(std::hypot(sites[i].x - sites[j].x, sites[i].y - sites[j].y), 2 * spec.radius - 1e-12);
}

TEST(MixingSamples, RadiusFromMassAndBadLayouts) {
  const double a = sample_radius_for_mass(0.46e-3, 1500, 0.02);
  EXPECT_NEAR(1500 * kPi * a * a * 0.02, 0.46e-3, 1e-15);

  SampleSpec s = annulus_samples();
  s.radius = 0.0051;  // wider than half the ring gap
  EXPECT_NE(sample_layout_problem(s).find("two sample radii"), std::string::npos) << sample_layout_problem(s);
  s = annulus_samples();
  s.spacing = 0.007;  // crowds the samples on the outer rings
  EXPECT_NE(sample_layout_problem(s).find("raise the spacing"), std::string::npos) << sample_layout_problem(s);
  EXPECT_THROW(SampleLayout{s}, std::invalid_argument);
  s = annulus_samples();
  s.ring_radii = {0, 0.02};  // a single sample on the axis
  const SampleLayout centre(s);
  EXPECT_EQ(centre.samples_on_ring(0), 1);
  EXPECT_EQ(centre.locate(s.center_x + 0.001, s.center_y - 0.001, 0.01), 0);
}

TEST(MixingTally, MassAndMarkerBalanceAgainstBruteForce) {
  const SampleSpec spec = annulus_samples();
  const SampleLayout layout(spec);
  std::mt19937_64 rng(7);
  ParticleSnapshot snap = random_bed(spec, 0.055, 20000, rng);
  for (std::size_t i = 0; i < snap.size(); ++i) snap.marker[i] = std::uint8_t(rng() % 3);  // 1 is the tracer

  const std::vector<SampleTally> tallies = tally_samples(layout, snap, 1);
  ASSERT_EQ(tallies.size(), layout.sites().size());
  std::vector<SampleTally> expect(layout.sites().size());
  long long in_samples = 0, total = 0;
  double mass_in_samples = 0;
  for (std::size_t i = 0; i < snap.size(); ++i) {
    int hits = 0;
    for (std::size_t s = 0; s < layout.sites().size(); ++s) {
      if (!inside(spec, layout.sites()[s], snap.position[i])) continue;
      ++hits;
      expect[s].particles += 1;
      expect[s].mass += snap.mass[i];
      if (snap.marker[i] == 1) {
        expect[s].tracers += 1;
        expect[s].tracer_mass += snap.mass[i];
      }
    }
    EXPECT_LE(hits, 1);
    in_samples += hits;
    if (hits) mass_in_samples += snap.mass[i];
  }
  double tallied_mass = 0;
  for (std::size_t s = 0; s < tallies.size(); ++s) {
    EXPECT_EQ(tallies[s].particles, expect[s].particles) << "sample " << s;
    EXPECT_EQ(tallies[s].tracers, expect[s].tracers) << "sample " << s;
    EXPECT_NEAR(tallies[s].mass, expect[s].mass, 1e-12);
    EXPECT_NEAR(tallies[s].tracer_mass, expect[s].tracer_mass, 1e-12);
    total += tallies[s].particles;
    tallied_mass += tallies[s].mass;
  }
  EXPECT_EQ(total, in_samples);
  EXPECT_NEAR(tallied_mass, mass_in_samples, 1e-12);
  EXPECT_GT(in_samples, 1000);  // the test samples something
}

MixingSpec mixing_spec() {
  MixingSpec m;
  m.samples = annulus_samples();
  m.every = 1;
  return m;
}

TEST(MixingStatistics, SegregatedBedHasLaceyZeroAndRsdOne) {
  const MixingSpec spec = mixing_spec();
  std::mt19937_64 rng(11);
  ParticleSnapshot snap = random_bed(spec.samples, 0.05, 100000, rng);
  for (std::size_t i = 0; i < snap.size(); ++i) snap.marker[i] = snap.position[i].x > spec.samples.center_x;
  const MixingResult r = evaluate_mixing(spec, snap);
  EXPECT_EQ(r.time, 1.5);
  EXPECT_EQ(r.step, 42);
  EXPECT_EQ(r.samples, r.samples_total);
  EXPECT_NEAR(r.concentration, 0.5, 0.05);
  // Only the few samples the plane x = centre cuts hold both species.
  EXPECT_NEAR(r.lacey, 0, 0.1);
  EXPECT_NEAR(r.rsd, 1, 0.1);
  EXPECT_NEAR(r.one_minus_rsd, 1 - r.rsd, 1e-15);
}

TEST(MixingStatistics, RandomBedHasLaceyOneWithinSamplingError) {
  MixingSpec spec = mixing_spec();
  std::mt19937_64 rng(12345);
  ParticleSnapshot snap = random_bed(spec.samples, 0.05, 100000, rng);
  std::bernoulli_distribution tracer(0.5);
  for (auto& m : snap.marker) m = tracer(rng);
  for (ConcentrationBasis basis : {ConcentrationBasis::number, ConcentrationBasis::mass}) {
    spec.basis = basis;
    const MixingResult r = evaluate_mixing(spec, snap);
    const double n = r.particles_per_sample, p = r.concentration;
    ASSERT_GT(n, 300);
    ASSERT_EQ(r.samples, 75);
    // For a random mixture s^2 estimates sr^2 = p(1-p)/n with relative standard
    // error sqrt(2/(m_S-1)); M - 1 = (sr^2 - s^2)/(s0^2 - sr^2) then has the
    // standard error sqrt(2/(m_S-1)) / (n-1). Five of them. The mass basis
    // scatters more (masses vary by +-50 %: (1 + 1/12) x the variance).
    const double sigma = std::sqrt(2.0 / (r.samples - 1)) / (n - 1);
    const double bias = basis == ConcentrationBasis::mass ? (1.0 / 12) / (n - 1) : 0;
    EXPECT_NEAR(r.lacey, 1 - bias, 5 * sigma * (1 + bias * n)) << "basis " << int(basis);
    // RSD = s / mean: sqrt((1-p)/(p n)) within five relative standard errors 1/sqrt(2(m_S-1)).
    const double rsd = std::sqrt((1 + bias * (n - 1)) * (1 - p) / (p * n));
    EXPECT_NEAR(r.rsd, rsd, 5 * rsd / std::sqrt(2.0 * (r.samples - 1))) << "basis " << int(basis);
  }
}

// A bed whose lower half is split by the plane x = c and whose upper half by
// y = c (a lower part turned a quarter against the upper one, nothing mixed).
// A full-height sample in two quadrants holds one species, in the other two
// half of each: s^2 = 1/8 = s0^2 / 2, so M = 1/2 (up to the samples the
// planes cut and sr^2 = s0^2 / n). Samples in two layers see each half
// alone: segregated, M = 0, as for the segregated bed above.
TEST(MixingStatistics, LayersTellTurnedLayersFromMixing) {
  MixingSpec spec = mixing_spec();
  std::mt19937_64 rng(21);
  ParticleSnapshot snap = random_bed(spec.samples, 0.05, 100000, rng);
  const double middle = spec.samples.bottom + 0.5 * spec.samples.height;
  for (std::size_t i = 0; i < snap.size(); ++i) {
    const Vec3d& x = snap.position[i];
    snap.marker[i] = x.z < middle ? x.x > spec.samples.center_x : x.y > spec.samples.center_y;
  }
  const MixingResult whole = evaluate_mixing(spec, snap);
  spec.samples.layers = 2;
  const MixingResult layered = evaluate_mixing(spec, snap);
  std::printf("[ measured ] Lacey of full-height samples %.3f, of samples in two layers %.3f\n", whole.lacey,
              layered.lacey);
  EXPECT_EQ(layered.samples_total, 2 * whole.samples_total);
  EXPECT_NEAR(whole.lacey, 0.5, 0.1);
  EXPECT_NEAR(layered.lacey, 0, 0.1);
  // Sample (site s, layer l) is s * layers + l.
  const SampleLayout layout(spec.samples);
  const SampleSite& site = layout.sites()[3];
  EXPECT_EQ(layout.locate(site.x, site.y, middle - 1e-6), 6);
  EXPECT_EQ(layout.locate(site.x, site.y, middle + 1e-6), 7);
  EXPECT_EQ(layout.locate(site.x, site.y, spec.samples.bottom + spec.samples.height), 7);
}

TEST(MixingStatistics, MinimumCountRuleAndUndefinedCases) {
  MixingSpec spec = mixing_spec();
  std::vector<SampleTally> t(6);
  const long long counts[] = {100, 104, 98, 102, 49, 0};
  for (std::size_t i = 0; i < t.size(); ++i) {
    t[i].particles = counts[i];
    t[i].tracers = counts[i] / 2 + long(i % 2);
    t[i].mass = double(counts[i]);
    t[i].tracer_mass = double(t[i].tracers);
  }
  // Median of the non-empty counts: 100; half of it is 50, so 49 and 0 drop out.
  MixingResult r = mixing_statistics(t, spec);
  EXPECT_EQ(r.min_count, 50);
  EXPECT_EQ(r.samples, 4);
  EXPECT_EQ(r.samples_total, 6);
  EXPECT_DOUBLE_EQ(r.particles_per_sample, 101);
  EXPECT_DOUBLE_EQ(r.concentration, (50 + 53 + 49 + 52) / 404.0);
  // Eq. 14 and 15 by hand.
  const double x[] = {50 / 100.0, 53 / 104.0, 49 / 98.0, 52 / 102.0};
  const double mean = (x[0] + x[1] + x[2] + x[3]) / 4;
  double ss = 0;
  for (double xi : x) ss += (xi - mean) * (xi - mean);
  const double s = std::sqrt(ss / 3), p = r.concentration;
  EXPECT_DOUBLE_EQ(r.mean_concentration, mean);
  EXPECT_DOUBLE_EQ(r.std_dev, s);
  EXPECT_DOUBLE_EQ(r.rsd, s / mean);
  EXPECT_NEAR(r.lacey, (p * (1 - p) - s * s) / (p * (1 - p) - p * (1 - p) / 101), 1e-12);

  spec.min_fill = 0;
  spec.min_particles = 1;
  EXPECT_EQ(mixing_statistics(t, spec).samples, 5);  // every non-empty sample
  for (auto& ti : t) ti.tracers = ti.tracer_mass = 0;  // p = 0: Lacey and RSD undefined
  r = mixing_statistics(t, spec);
  EXPECT_TRUE(std::isnan(r.lacey));
  EXPECT_TRUE(std::isnan(r.rsd));
  r = mixing_statistics(std::vector<SampleTally>(1, t[0]), spec);  // one sample: no s
  EXPECT_EQ(r.samples, 1);
  EXPECT_TRUE(std::isnan(r.std_dev));
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(MixingLog, HeaderOnceThenOneRowPerEvaluation) {
  const std::string path = testing::TempDir() + "gs_test_mixing_log.csv";
  std::remove(path.c_str());
  MixingResult r;
  r.time = 21.166;
  r.step = 2000;
  r.lacey = 0.75;
  r.rsd = 0.125;
  r.one_minus_rsd = 0.875;
  r.samples = 44;
  r.particles_per_sample = 39.5;
  r.concentration = 0.5;
  {
    MixingLog log(path, 10.583, 0);
    log.append(r);
  }
  MixingLog again(path);  // continues the file, no second header, no revolutions
  r.lacey = std::nan("");
  again.append(r);
  const auto lines = lines_of(path);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "time,step,revolutions,lacey,rsd,one_minus_rsd,samples,particles_per_sample,concentration");
  EXPECT_EQ(lines[1], "21.166,2000,2,0.75,0.125,0.875,44,39.5,0.5");
  EXPECT_EQ(lines[2], "21.166,2000,,nan,0.125,0.875,44,39.5,0.5");
  std::ofstream(path) << "something else\n";
  EXPECT_THROW(MixingLog{path}, std::runtime_error);
  std::remove(path.c_str());
}

const std::string kScene = R"(domain: {min: [-0.06, -0.06, 0], max: [0.06, 0.06, 0.1]}
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
particles:
  - list:
      - {position: [0, 0, 0.05], radius: 0.002, material: glass}
time_step: {fraction_of_contact_time: 0.1}
duration: 40
analysis:
  mixing:
    center: [0, 0]
    bottom: 0.001
    height: 0.02
    rings: {inner_radius: 0.01, outer_radius: 0.05, count: 4}
    sample_mass: 0.00046
    bulk_density: 1500
    revolution_period: 10.583
    output: mix.csv
)";

std::string scene_error(const std::string& from, const std::string& to) {
  std::string text = kScene;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  try {
    parse_scene(text, "scene.yaml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MixingScene, KeysParse) {
  const SceneSpec s = parse_scene(kScene, "scene.yaml");
  ASSERT_TRUE(s.mixing.has_value());
  const MixingSpec& m = *s.mixing;
  ASSERT_EQ(m.samples.ring_radii.size(), 4u);
  EXPECT_DOUBLE_EQ(m.samples.ring_radii[3], 0.045);
  EXPECT_DOUBLE_EQ(m.samples.spacing, 0.01);  // the ring width by default
  EXPECT_NEAR(1500 * kPi * m.samples.radius * m.samples.radius * 0.02, 0.00046, 1e-12);
  EXPECT_EQ(m.every, 10.583);  // revolution_period by default
  EXPECT_EQ(m.output, "mix.csv");
  EXPECT_EQ(m.tracer_marker, 1);
  EXPECT_EQ(m.basis, ConcentrationBasis::number);
  EXPECT_EQ(m.samples.layers, 1);
  EXPECT_FALSE(parse_scene(kScene.substr(0, kScene.find("analysis:")), "scene.yaml").mixing.has_value());
  // Layers: each holds the sample mass, so the cylinders widen by sqrt(layers).
  std::string layered = kScene;
  layered.replace(layered.find("    output: mix.csv"), 19, "    output: mix.csv\n    layers: 2");
  const SampleSpec two = parse_scene(layered, "scene.yaml").mixing->samples;
  EXPECT_EQ(two.layers, 2);
  EXPECT_NEAR(1500 * kPi * two.radius * two.radius * 0.01, 0.00046, 1e-12);
}

TEST(MixingScene, ErrorsNameLineAndKey) {
  auto expect = [](const std::string& msg, const std::string& where, const std::string& what) {
    EXPECT_EQ(msg.rfind("scene.yaml:" + where, 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  };
  expect(scene_error("    output: mix.csv", "    outptu: mix.csv"), "20: analysis.mixing.outptu", "unknown key");
  expect(scene_error("    sample_mass: 0.00046\n", "    sample_mass: 0.00046\n    sample_radius: 0.004\n"),
         "12: analysis.mixing", "exactly one of {sample_radius, sample_mass}");
  expect(scene_error("sample_mass: 0.00046", "sample_mass: 0.004"), "17: analysis.mixing.sample_mass",
         "too wide for rings");
  expect(scene_error("    revolution_period: 10.583\n", ""), "12: analysis.mixing", "missing required key 'every'");
  expect(scene_error("rings: {inner_radius: 0.01, outer_radius: 0.05, count: 4}", "ring_radii: [0.02, 0.01]"),
         "16: analysis.mixing.ring_radii[1]", "ascending");
  expect(scene_error("outer_radius: 0.05", "outer_radius: 0.07"), "12: analysis.mixing", "outside the domain");
  expect(scene_error("center: [0, 0]", "center: [0, 0, 0]"), "13: analysis.mixing.center", "[x, y]");
  expect(scene_error("    output: mix.csv", "    output: mix.csv\n    layers: 0"), "21: analysis.mixing.layers",
         "[1, 1000]");
}

}  // namespace
}  // namespace gs
