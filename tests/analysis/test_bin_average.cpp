// Bin and region averages (analysis/bin_average.hpp) against closed forms and
// an independent computation: a simple cubic lattice fills pi/6 of space; a
// gas of particles with known velocities gives the kinetic stress and
// granular temperature computed here in long double; a static simple cubic
// column under gravity, squeezed sideways by walls, has coordination 6 inside
// and the contact stress of its known contact forces, sigma_zz = rho_bulk g
// depth (the contact pass of engine/contact_measure_kernel.hpp, per backend).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "analysis/bin_average.hpp"
#include "support/support.hpp"

namespace gs::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

ParticleSnapshot lattice_snapshot(int n, double radius, double spacing) {
  ParticleSnapshot s;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        s.id.push_back(ParticleId(s.id.size()));
        s.position.push_back(Vec3d((i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing));
        s.velocity.push_back({});
        s.radius.push_back(float(radius));
        s.mass.push_back(1.0f);
        s.material.push_back(0);
        s.marker.push_back(0);
      }
  return s;
}

AverageSpec box_spec(Vec3d min, Vec3d max, std::array<int, 3> bins) {
  AverageSpec a;
  a.min = min;
  a.max = max;
  a.bins = bins;
  a.quantities = all_quantities();
  return a;
}

// Touching spheres on a simple cubic lattice: pi/6 of every bin that holds
// whole lattice cells (2 x 2 x 2 here); the centre assignment counts each
// sphere whole in the bin of its centre.
TEST(BinAverage, SimpleCubicLatticeFillsPiOverSix) {
  const double r = 0.5, a = 2 * r;
  const ParticleSnapshot s = lattice_snapshot(10, r, a);
  const std::vector<BinAverage> bins = bin_averages(box_spec({0, 0, 0}, {10 * a, 10 * a, 10 * a}, {5, 5, 5}), s, {});
  ASSERT_EQ(bins.size(), 125u);
  for (const BinAverage& b : bins) {
    EXPECT_EQ(b.particles, 8);
    EXPECT_NEAR(b.solid_fraction, kPi / 6, 1e-14);
  }
  // One region over the lattice.
  EXPECT_NEAR(bin_averages(box_spec({0, 0, 0}, {10 * a, 10 * a, 10 * a}, {1, 1, 1}), s, {})[0].solid_fraction,
              kPi / 6, 1e-14);
}

TEST(BinAverage, BinOfPointsOnFacesAndOutside) {
  const AverageSpec a = box_spec({0, 0, 0}, {1, 2, 3}, {2, 2, 3});
  EXPECT_EQ(bin_of(a, {0, 0, 0}), 0);
  EXPECT_EQ(bin_of(a, {1, 2, 3}), 11);  // the max corner is in the last bin
  EXPECT_EQ(bin_of(a, {0.75, 0.5, 1.5}), 1 + 2 * (0 + 2 * 1));
  EXPECT_EQ(bin_of(a, {1.0000001, 1, 1}), -1);
  EXPECT_EQ(bin_of(a, {0.5, -1e-9, 1}), -1);
}

// Particles of random masses and velocities in two bins: the mean velocity,
// temperature and kinetic stress of each, summed here independently in long
// double over the particles of each bin.
TEST(BinAverage, GasGivesTheKineticStressAndTemperature) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  ParticleSnapshot s;
  for (int i = 0; i < 400; ++i) {
    s.id.push_back(ParticleId(i));
    s.position.push_back({2 * unit(rng), unit(rng), unit(rng)});
    s.velocity.push_back({3 * unit(rng) - 1, unit(rng) - 0.5, 0.2 * unit(rng) + 4});
    s.mass.push_back(float(0.5 + unit(rng)));
    s.radius.push_back(0.01f);
    s.material.push_back(0);
    s.marker.push_back(0);
  }
  const AverageSpec spec = box_spec({0, 0, 0}, {2, 1, 1}, {2, 1, 1});
  const std::vector<BinAverage> bins = bin_averages(spec, s, {});
  for (int b = 0; b < 2; ++b) {
    long double mass = 0, p[3] = {0, 0, 0};
    auto in_bin = [&](std::size_t i) { return (s.position[i].x >= 1) == (b == 1); };
    auto component = [](const Vec3d& v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; };
    for (std::size_t i = 0; i < s.size(); ++i)
      if (in_bin(i)) {
        mass += s.mass[i];
        for (int c = 0; c < 3; ++c) p[c] += (long double)s.mass[i] * component(s.velocity[i], c);
      }
    long double u[3], stress[3][3] = {}, fluctuation = 0;
    for (int c = 0; c < 3; ++c) u[c] = p[c] / mass;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (in_bin(i))
        for (int c = 0; c < 3; ++c) {
          const long double vc = component(s.velocity[i], c) - u[c];
          fluctuation += s.mass[i] * vc * vc;
          for (int d = 0; d < 3; ++d) stress[c][d] += s.mass[i] * vc * (component(s.velocity[i], d) - u[d]);
        }
    const BinAverage& a = bins[std::size_t(b)];
    EXPECT_NEAR(a.mass, double(mass), 1e-12);
    EXPECT_NEAR(a.velocity.x, double(u[0]), 1e-13);
    EXPECT_NEAR(a.velocity.z, double(u[2]), 1e-13);
    EXPECT_NEAR(a.granular_temperature, double(fluctuation / (3 * mass)), 1e-13);
    const Vec3d* rows[3] = {&a.kinetic_stress.x, &a.kinetic_stress.y, &a.kinetic_stress.z};
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(component(*rows[c], d), double(stress[c][d] / 1.0L), 1e-11);
    // T is a third of the trace of the kinetic stress per unit mass density.
    EXPECT_NEAR(a.granular_temperature, (a.kinetic_stress.x.x + a.kinetic_stress.y.y + a.kinetic_stress.z.z) /
                                            (3 * a.mass), 1e-13);
  }
}

// A 3 x 3 x 6 simple cubic column of spheres resting on a floor, squeezed
// sideways by four walls with overlap delta_l, each layer placed at its
// static overlap: the contact between layers j and j+1 (j counted from the
// top) carries the weight of j particles, K delta_j = j m g, the floor N m g.
constexpr double kRadius = 0.0009765625, kDensity = 2500, kStiffness = 1000, kGravity = 9.81;
constexpr int kLayers = 6;
constexpr double kSideOverlap = 2e-7;

struct Column {
  SceneSpec scene;
  std::vector<double> z;  // centre of layer j (from the top, j = 1..N) at index j - 1
  double lateral = 0;     // centre distance across
};

Column resting_column(unsigned effects) {
  Column c;
  SceneSpec& scene = c.scene;
  scene = base_scene(kDensity, kStiffness, 0.5, effects ? 0.5 : 0.0);
  scene.effects = effects;
  scene.gravity = {0, 0, -kGravity};
  const double m = stored_sphere_mass(kRadius, kDensity);
  c.lateral = 2 * kRadius - kSideOverlap;
  c.z.assign(kLayers, 0);
  c.z[kLayers - 1] = kRadius - kLayers * m * kGravity / kStiffness;
  for (int j = kLayers - 1; j >= 1; --j) c.z[std::size_t(j - 1)] = c.z[std::size_t(j)] + 2 * kRadius - j * m * kGravity / kStiffness;
  const double wall = c.lateral + kRadius - kSideOverlap;
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1}),     plane_wall({-wall, 0, 0}, {1, 0, 0}),
                 plane_wall({wall, 0, 0}, {-1, 0, 0}), plane_wall({0, -wall, 0}, {0, 1, 0}),
                 plane_wall({0, wall, 0}, {0, -1, 0})};
  scene.domain_min = {-0.004, -0.004, -0.001};
  scene.domain_max = {0.004, 0.004, 0.014};
  ParticleId id = 0;
  for (int j = 0; j < kLayers; ++j)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) scene.particles.push_back(particle(id++, kRadius, {x * c.lateral, y * c.lateral, c.z[std::size_t(j)]}));
  scene.time_step = 1e-5;
  return c;
}

// The central column's particles, one per bin of height 2 r.
AverageSpec central_bins(const Column& c) {
  return box_spec({-c.lateral / 2, -c.lateral / 2, 0}, {c.lateral / 2, c.lateral / 2, kLayers * 2 * kRadius},
                  {1, 1, kLayers});
}

void expect_column_stress(const Column& c, const ParticleSnapshot& s, const std::vector<ContactMeasure>& contacts) {
  const AverageSpec spec = central_bins(c);
  const std::vector<BinAverage> bins = bin_averages(spec, s, contacts);
  const double m = stored_sphere_mass(kRadius, kDensity), volume = c.lateral * c.lateral * 2 * kRadius;
  const double rho_bulk = m / volume;
  for (int j = 1; j <= kLayers; ++j) {
    SCOPED_TRACE("layer " + std::to_string(j) + " from the top");
    const BinAverage& b = bins[std::size_t(kLayers - j)];  // bins count up from the floor
    ASSERT_EQ(b.particles, 1);
    // Particle contacts: four sideways, one above (but the top), one below (but the bottom).
    EXPECT_EQ(b.coordination, 4 + (j > 1) + (j < kLayers));
    // Half of each branch (x) force; the floor's branch from its contact point, whole.
    double moment = 0;
    if (j > 1) moment += 0.5 * (c.z[std::size_t(j - 2)] - c.z[std::size_t(j - 1)]) * (j - 1) * m * kGravity;
    if (j < kLayers) moment += 0.5 * (c.z[std::size_t(j - 1)] - c.z[std::size_t(j)]) * j * m * kGravity;
    else moment += c.z[std::size_t(j - 1)] * kLayers * m * kGravity;
    EXPECT_NEAR(b.contact_stress.z.z, moment / volume, 1e-9 * moment / volume);
    // The weight above the layer's middle, to the overlaps' order (1e-4).
    const double depth = (j - 0.5) * 2 * kRadius;
    EXPECT_NEAR(b.contact_stress.z.z / (rho_bulk * kGravity * depth), 1.0, 1e-3);
    const double sideways = c.lateral * kStiffness * kSideOverlap / volume;
    EXPECT_NEAR(b.contact_stress.x.x, sideways, 1e-6 * sideways);
    EXPECT_NEAR(b.contact_stress.y.y, sideways, 1e-6 * sideways);
    for (double off : {b.contact_stress.x.y, b.contact_stress.x.z, b.contact_stress.y.z, b.contact_stress.z.x})
      EXPECT_LT(std::abs(off), 1e-9 * moment / volume);
  }
}

class ColumnTest : public testing::TestWithParam<Backend> {};

TEST_P(ColumnTest, RestingColumnHasCoordinationSixAndItsWeightAsStress) {
  for (unsigned effects : {0u, unsigned(kFriction)}) {
    SCOPED_TRACE(effects ? "friction" : "no friction");
    const Column c = resting_column(effects);
    Simulation sim(c.scene, {GetParam()});
    sim.measure_contacts_at(0);  // at once: the simulation is at step 0
    expect_column_stress(c, sim.snapshot(), sim.contact_measures());
    // After the force computation of step 20, within the run.
    sim.measure_contacts_at(20);
    sim.run(19);
    EXPECT_THROW(sim.contact_measures(), std::logic_error);  // no pass at step 19
    sim.run(1);
    expect_column_stress(c, sim.snapshot(), sim.contact_measures());
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ColumnTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
