// What accuracy costs in time: runs reference scenes over a grid of
// precision (fp32 forces, fp64, fp32 throughout) x time step (fraction of the contact time) x contact model and
// prints, per point, the error against a fp64, small-step reference of the
// same model and the wall time (CSV on stdout; bench/plot_accuracy.py draws
// error against wall time). Scenes:
//   impact  two-sphere head-on impact: restitution and contact time
//   gas     1000 elastic frictionless spheres in a box: energy drift
//   bed     800 frictional spheres settled for 0.15 s: packing fraction, coordination
//
//   accuracy_study [--backend cpu|cuda] [--scenes impact,gas,bed]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scene/scene_time_step.hpp"
#include "comm/transport.hpp"
#include "engine/simulation.hpp"
#include "run/driver.hpp"
#include "scene/generators.hpp"

namespace {

using namespace gs;

constexpr double kRadius = 1e-3, kDensity = 2500, kStiffness = 2e3;
// Hertz modulus giving about the linear contact time at the impact speed.
constexpr double kYoungs = 5e6, kPoisson = 0.25;

struct Point {
  ContactModel model;
  Precision precision;
  double fraction;  // time step / contact time
};

struct Measure {
  std::vector<double> values;  // the scene's observables
  double wall = 0;
};

Wall plane(Vec3d point, Vec3d normal) {
  Wall w;
  w.kind = WallKind::plane;
  w.point = point;
  w.normal = normal;
  return w;
}

SceneSpec base(const Point& p, double restitution, double friction, Vec3d lo, Vec3d hi) {
  SceneSpec s;
  s.path = "accuracy_study";
  s.model = p.model;
  s.precision = p.precision;
  s.domain_min = lo;
  s.domain_max = hi;
  s.materials.push_back({"m", kDensity, kYoungs, kPoisson});
  PairSpec pair;
  pair.stiffness_normal = kStiffness;
  pair.stiffness_tangential = kStiffness * 2 / 7;
  pair.stiffness_rolling = pair.stiffness_tangential;
  pair.restitution = restitution;
  pair.friction = friction;
  s.pairs.push_back(pair);
  s.effects = friction > 0 ? kFriction : 0u;
  s.duration = 1;
  return s;
}

void set_step(SceneSpec& s, const Point& p) {
  s.contact_time = critical_contact_time(s);
  s.time_step = p.fraction * s.contact_time;
}

// A run of the scene started as every run starts (run/driver.hpp), on this
// process alone, with its packing checked.
std::unique_ptr<Simulation> start(SceneSpec& s, Backend b) {
  static const std::unique_ptr<Transport> transport = make_single_transport();
  SceneStart run;
  run.options.backend = b;
  return start_scene(s, run, *transport);
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Restitution and contact time of a head-on impact at 1 m/s.
Measure impact(const Point& p, Backend b) {
  SceneSpec s = base(p, 0.7, 0, {-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01});
  ParticleInit a, c;
  a.id = 0, a.radius = kRadius, a.position = {-1.001 * kRadius, 0, 0}, a.velocity = {0.5, 0, 0};
  c.id = 1, c.radius = kRadius, c.position = {1.001 * kRadius, 0, 0}, c.velocity = {-0.5, 0, 0};
  s.particles = {a, c};
  set_step(s, p);
  const auto t0 = std::chrono::steady_clock::now();
  const std::unique_ptr<Simulation> started = start(s, b);
  Simulation& sim = *started;
  // Contact starts and ends where the gap changes sign, interpolated
  // linearly within the step (so the step itself does not quantise it).
  double start = -1, end = -1, gap_before = 0.002 * kRadius, time_before = 0;
  while (end < 0 && sim.time() < 0.01) {
    sim.run(1);
    const ParticleSnapshot snap = sim.snapshot();
    const double gap = norm(snap.position[1] - snap.position[0]) - 2 * kRadius;
    const double crossing = time_before + (sim.time() - time_before) * gap_before / (gap_before - gap);
    if (gap < 0 && start < 0) start = crossing;
    if (gap >= 0 && start >= 0) end = crossing;
    gap_before = gap;
    time_before = sim.time();
  }
  const ParticleSnapshot snap = sim.snapshot();
  return {{snap.velocity[1].x - snap.velocity[0].x, end - start}, seconds(t0)};  // approach speed 1 m/s
}

// Relative drift of kinetic + elastic energy of an elastic gas after 20 contact times.
Measure gas(const Point& p, Backend b) {
  SceneSpec s = base(p, 1.0, 0, {-0.011, -0.011, -0.011}, {0.011, 0.011, 0.011});
  s.walls = {plane({-0.01, 0, 0}, {1, 0, 0}), plane({0.01, 0, 0}, {-1, 0, 0}), plane({0, -0.01, 0}, {0, 1, 0}),
             plane({0, 0.01, 0}, {0, -1, 0}), plane({0, 0, -0.01}, {0, 0, 1}), plane({0, 0, 0.01}, {0, 0, -1})};
  std::mt19937_64 rng(11);
  std::normal_distribution<double> v(0, 0.3);
  ParticleId id = 0;
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        ParticleInit q;
        q.id = id++;
        q.radius = kRadius * 0.7;
        q.position = {-0.009 + 0.002 * i, -0.009 + 0.002 * j, -0.009 + 0.002 * k};
        q.velocity = {v(rng), v(rng), v(rng)};
        s.particles.push_back(q);
      }
  set_step(s, p);
  // Stored elastic energy of an overlap d: k d^2 / 2 (linear) or
  // 8/15 E* sqrt(R*) d^(5/2) (Hertz).
  const double youngs_eff = kYoungs / (2 * (1 - kPoisson * kPoisson));
  auto spring = [&](double d, double r_eff) {
    if (d <= 0) return 0.0;
    return p.model == ContactModel::linear ? 0.5 * kStiffness * d * d
                                           : 8.0 / 15.0 * youngs_eff * std::sqrt(r_eff) * std::pow(d, 2.5);
  };
  auto energy = [&](const ParticleSnapshot& snap) {
    double e = 0;
    for (std::size_t i = 0; i < snap.size(); ++i) {
      const double ri = snap.radius[i];
      e += 0.5 * snap.mass[i] * norm2(snap.velocity[i]);
      for (std::size_t j = i + 1; j < snap.size(); ++j) {
        const double rj = snap.radius[j];
        e += spring(ri + rj - norm(snap.position[i] - snap.position[j]), ri * rj / (ri + rj));
      }
      for (const Wall& w : s.walls) e += spring(ri - dot(snap.position[i] - w.point, w.normal), ri);
    }
    return e;
  };
  const auto t0 = std::chrono::steady_clock::now();
  const std::unique_ptr<Simulation> started = start(s, b);
  Simulation& sim = *started;
  const double e0 = energy(sim.snapshot());
  sim.run(std::llround(20 * s.contact_time / s.time_step));
  const double wall = seconds(t0);
  return {{std::abs(energy(sim.snapshot()) - e0) / e0}, wall};
}

// Packing fraction of the lower half of a settled bed and mean coordination.
Measure bed(const Point& p, Backend b) {
  SceneSpec s = base(p, 0.5, 0.5, {-0.001, -0.001, -0.001}, {0.021, 0.021, 0.061});
  s.gravity = {0, 0, -9.81};
  s.walls = {plane({0, 0, 0}, {1, 0, 0}), plane({0.02, 0, 0}, {-1, 0, 0}), plane({0, 0, 0}, {0, 1, 0}),
             plane({0, 0.02, 0}, {0, -1, 0}), plane({0, 0, 0}, {0, 0, 1})};
  RandomFillSpec fill;
  fill.region.min = {0.0012, 0.0012, 0.0012};
  fill.region.max = {0.0188, 0.0188, 0.03};
  fill.count = 800;
  fill.size.kind = SizeSpec::Kind::uniform;
  fill.size.radius_min = 0.0008;
  fill.size.radius_max = 0.0011;
  fill.seed = 5;
  generate_random_fill(fill, s.particles);
  set_step(s, p);
  const auto t0 = std::chrono::steady_clock::now();
  const std::unique_ptr<Simulation> started = start(s, b);
  Simulation& sim = *started;
  sim.run(std::llround(0.15 / s.time_step));
  const double wall = seconds(t0);
  const ParticleSnapshot snap = sim.snapshot();
  double solid = 0, zmax = 0;
  for (std::size_t i = 0; i < snap.size(); ++i) zmax = std::max(zmax, snap.position[i].z);
  const double h = 0.5 * zmax;
  long long bonds = 0;
  for (std::size_t i = 0; i < snap.size(); ++i) {
    const double r = snap.radius[i];
    if (snap.position[i].z < h) solid += 4.0 / 3.0 * M_PI * r * r * r;
    for (std::size_t j = 0; j < snap.size(); ++j)
      if (j != i && norm(snap.position[i] - snap.position[j]) < r + double(snap.radius[j])) ++bonds;
  }
  return {{solid / (0.02 * 0.02 * h), double(bonds) / double(snap.size())}, wall};
}

double relative_error(const std::vector<double>& v, const std::vector<double>& ref) {
  double e = 0;
  for (std::size_t k = 0; k < v.size(); ++k)
    e = std::max(e, ref[k] != 0 ? std::abs(v[k] - ref[k]) / std::abs(ref[k]) : std::abs(v[k]));
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  Backend backend = default_backend();
  std::string scenes = "impact,gas,bed";
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string a = argv[k], v = argv[k + 1];
    if (a == "--backend") backend = parse_backend(v);
    else if (a == "--scenes") scenes = v;
  }
  const std::vector<std::pair<std::string, std::function<Measure(const Point&, Backend)>>> all = {
      {"impact", impact}, {"gas", gas}, {"bed", bed}};
  std::printf("backend,scene,model,precision,fraction,wall_s,error,values\n");
  for (const auto& [name, run] : all) {
    if (scenes.find(name) == std::string::npos) continue;
    for (ContactModel model : {ContactModel::linear, ContactModel::hertz_mindlin}) {
      // Reference: fp64 forces and a fifth of the smallest step of the grid;
      // the gas's own error is its drift, measured against zero.
      const Measure ref = run({model, Precision::fp64, 0.005}, backend);
      for (Precision precision : {Precision::fp32, Precision::fp64, Precision::fp32_full})
        for (double fraction : {0.025, 0.05, 0.1, 0.2}) {
          const Measure m = run({model, precision, fraction}, backend);
          const double error = name == "gas" ? m.values[0] : relative_error(m.values, ref.values);
          std::ostringstream values;
          for (double x : m.values) values << x << ";";
          std::printf("%s,%s,%s,%s,%g,%.4g,%.4g,%s\n", backend_name(backend), name.c_str(),
                      model == ContactModel::linear ? "linear" : "hertz",
                      precision_name(precision), fraction, m.wall, error, values.str().c_str());
          std::fflush(stdout);
        }
    }
  }
  return 0;
}
