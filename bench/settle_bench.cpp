// Throughput of a bed of N spheres: particle-steps per second and device
// bytes per particle. The bed is a cubic lattice pressed 0.5 % into overlap
// under gravity in a box, so every particle starts with about six contacts.
// The box leaves room (a spacing at two side walls, 2 r above the top), so the
// overlaps push the lattice apart: at the default step, 5.9 contacts per
// sphere at step 20, 5.5 at step 70, 3.2 at step 220, 1.6 at step 420
// (--n 100000; at the 0.2 contact times stepped until 2026-12-07, 5.7 at
// step 20, 4.1 at 70 and under one from 220 on). Short runs (--steps 50)
// time the dense bed, long ones mostly a loose, moving one; the output line
// ends with the contacts per particle (walls included) after the timed steps
// (-1 without friction, which keeps no contact history, or with --contacts no), then the Verlet
// list's builds in the warm-up and the timed steps. integrate_s, neighbours_s and forces_s
// split the warm-up's and the timed steps' time (Simulation::timings: every list build timed).
//
//   settle_bench [--n N] [--steps S] [--backend cpu|cuda] [--precision fp32|fp64|fp32_full]
//                [--effects none|friction|rolling|cohesion] [--model linear|hertz]
//                [--mesh impeller]   (the seed's impeller turning at 30 rpm in the bed; needs
//                                     --n 63701 or more: smaller lattices can lie wholly in
//                                     the cylinder the impeller sweeps, 99 mm across, 104 mm tall)
//                [--skin S]          (Verlet list skin in largest diameters, default 0.1)
//                [--step F]          (time step as a fraction of the contact time, default 0.1;
//                                     refused above the stability limit, 0.116 with friction,
//                                     as the scene loader refuses it: docs/STABILITY.md)
//                [--contacts no]     (skip the count of contacts at the end, a host copy of the
//                                     whole state: the largest beds, whose host memory it would pass)
//                [--digest yes]      (then print the final state's digest: the same for any build
//                                     that computes the same bits)
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "backend/memory.hpp"
#include "scene/scene_time_step.hpp"
#include "contact/contact_models.hpp"
#include "comm/transport.hpp"
#include "engine/simulation.hpp"
#include "run/driver.hpp"
#include "io/state_digest.hpp"
#include "walls/impeller.hpp"
#include "walls/mesh.hpp"

namespace {

struct Options {
  long long n = 100000;
  long long steps = 200;
  gs::Precision precision = gs::Precision::fp32;
  unsigned effects = gs::kFriction;
  gs::ContactModel model = gs::ContactModel::linear;
  bool mesh = false;  // the seed's impeller turning at 30 rpm in the bed
  bool digest = false;  // print the final state's digest (io/state_digest.hpp) after the timing
  bool contacts = true;  // count the contacts per particle at the end (a host snapshot)
  double skin = gs::kDefaultVerletSkin;  // Verlet list skin, largest diameters
  // Time step in contact times: the cases' 0.1-0.11, within the loader's
  // limit (until 2026-12-07 the bench stepped at 0.2, beyond it).
  double step = 0.1;
  gs::RunOptions run{gs::default_backend()};  // backend
};

gs::Precision parse_precision(const std::string& s) {
  for (gs::Precision p : {gs::Precision::fp32, gs::Precision::fp64, gs::Precision::fp32_full})
    if (s == gs::precision_name(p)) return p;
  throw std::invalid_argument("--precision must be fp32, fp64 or fp32_full");
}

unsigned parse_effects(const std::string& s) {
  if (s == "none") return 0;
  if (s == "friction") return gs::kFriction;
  if (s == "rolling") return gs::kFriction | gs::kRollingResistance;
  if (s == "cohesion") return gs::kFriction | gs::kRollingResistance | gs::kCohesion;
  throw std::invalid_argument("--effects must be none, friction, rolling or cohesion");
}

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (k + 1 >= argc) throw std::invalid_argument("option " + a + " needs a value");
    const std::string v = argv[++k];
    if (a == "--n") o.n = std::stoll(v);
    else if (a == "--steps") o.steps = std::stoll(v);
    else if (a == "--backend") o.run.backend = gs::parse_backend(v);
    else if (a == "--precision") o.precision = parse_precision(v);
    else if (a == "--effects") o.effects = parse_effects(v);
    else if (a == "--model") o.model = v == "hertz" ? gs::ContactModel::hertz_mindlin : gs::ContactModel::linear;
    else if (a == "--mesh") o.mesh = v == "impeller";
    else if (a == "--digest") o.digest = v == "yes";
    else if (a == "--contacts") o.contacts = v != "no";
    else if (a == "--skin") o.skin = std::stod(v);
    else if (a == "--step") o.step = std::stod(v);
    else throw std::invalid_argument("unknown option " + a);
  }
  return o;
}

gs::Wall box_side(gs::Vec3d point, gs::Vec3d normal) {
  gs::Wall w;
  w.kind = gs::WallKind::plane;
  w.point = point;
  w.normal = normal;
  w.material = 0;
  return w;
}

// Glass-like spheres of 1 mm radius on a square-based lattice 1.5x as tall as wide.
gs::SceneSpec bed_scene(const Options& o) {
  const double r = 1e-3, spacing = 2 * r * 0.995;
  const long long side = std::llround(std::cbrt(double(o.n) / 1.5));
  const long long layers = (o.n + side * side - 1) / (side * side);
  gs::SceneSpec s;
  s.path = "settle_bench";
  s.model = o.model;
  s.precision = o.precision;
  s.effects = o.effects;
  s.gravity = {0, 0, -9.81};
  const double width = side * spacing + 2 * r, height = layers * spacing + 4 * r;
  s.domain_min = {-r, -r, -r};
  s.domain_max = {width + r, width + r, height + r};
  s.materials.push_back({"glass", 2500, 6e7, 0.25});
  gs::PairSpec p;
  p.stiffness_normal = 2e3;
  p.stiffness_tangential = p.stiffness_normal * 2 / 7;
  p.stiffness_rolling = p.stiffness_tangential;
  p.restitution = 0.5;
  p.friction = 0.5;
  p.rolling_friction = 0.05;
  p.cohesion_energy_density = 1e3;
  s.pairs.push_back(p);
  const double lo = r + 1e-6;
  s.walls = {box_side({0, 0, 0}, {1, 0, 0}), box_side({width, 0, 0}, {-1, 0, 0}), box_side({0, 0, 0}, {0, 1, 0}),
             box_side({0, width, 0}, {0, -1, 0}), box_side({0, 0, 0}, {0, 0, 1}),
             box_side({0, 0, height}, {0, 0, -1})};
  // The impeller (hub, shaft, 4 blades; 95 mm across) stands on the floor in
  // the middle of the bed; particles in the cylinder it sweeps are left out.
  const gs::Vec3d centre(width / 2, width / 2, 2 * r);
  const gs::ImpellerSpec impeller;
  const double swept = impeller.blade_diameter / 2 + 2 * r;
  const double top = centre.z + impeller.hub_height + impeller.shaft_length + 2 * r;
  if (o.mesh) {
    gs::TriangleMesh m = gs::make_impeller(impeller);
    for (gs::Vec3d& v : m.vertices) v += centre;
    m.name = "impeller";
    gs::add_mesh(s.meshes, m, 0, gs::rotation_at_rpm(centre, {0, 0, 1}, 30));
  }
  for (long long k = 0; k < o.n; ++k) {
    gs::ParticleInit q;
    q.id = gs::ParticleId(k);
    q.radius = r;
    q.position = {lo + double(k % side) * spacing, lo + double((k / side) % side) * spacing,
                  lo + double(k / (side * side)) * spacing};
    const double dx = q.position.x - centre.x, dy = q.position.y - centre.y;
    if (o.mesh && dx * dx + dy * dy < swept * swept && q.position.z < top) continue;
    s.particles.push_back(q);
  }
  // Else the run fails later, and cryptically ("cell size must be positive").
  if (s.particles.empty())
    throw std::invalid_argument("--mesh impeller: every sphere of --n " + std::to_string(o.n) +
                                " lies in the cylinder the impeller sweeps (63701 or more leave some outside)");
  s.contact_time = gs::critical_contact_time(s);
  // The loader's rule: no step a scene file could not ask for.
  s.time_step = o.step * s.contact_time;
  if (const std::string problem = gs::time_step_problem(s); !problem.empty())
    throw std::invalid_argument("--step: " + problem);
  s.duration = s.time_step * double(o.steps);
  s.verlet_skin = o.skin;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    gs::SceneSpec scene = bed_scene(o);
    // Started as every run starts (run/driver.hpp); the bed is pressed into
    // overlap on purpose, so the packing checks stay off.
    const std::unique_ptr<gs::Transport> transport = gs::make_single_transport();
    gs::SceneStart start;
    start.options = o.run;
    start.check_packing = false;
    const std::unique_ptr<gs::Simulation> started = gs::start_scene(scene, start, *transport);
    gs::Simulation& sim = *started;
    sim.run(20);  // warm up: first sorts, history slots claimed
    const auto t0 = std::chrono::steady_clock::now();
    sim.run(o.steps);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double n = double(scene.particles.size());
    const double rate = double(o.steps) * n / wall;
    const double bytes = double(gs::backend_peak_bytes(o.run.backend)) / n;
    const gs::StepTimings t = sim.timings();
    // What the timed steps ended with: the bed loosens as it runs (see the top).
    double contacts = -1;
    if (o.contacts && gs::keeps_history(o.model, o.effects)) {
      const gs::ParticleSnapshot end = sim.snapshot();
      contacts = 0;
      for (std::uint16_t c : end.contacts) contacts += c;
      contacts /= n;
    }
    std::printf("backend=%s n=%zu mesh=%s precision=%s effects=%u model=%s steps=%lld step_fraction=%g "
                "time_step_s=%.6g wall_s=%.3f "
                "particle_steps_per_s=%.4g peak_bytes_per_particle=%.1f held_bytes_per_particle=%.1f "
                "integrate_s=%.3f neighbours_s=%.3f forces_s=%.3f contacts_per_particle_at_end=%.2f list_builds=%lld "
                "reserved_bytes_per_particle=%.1f\n",
                gs::backend_name(o.run.backend), scene.particles.size(), o.mesh ? "impeller" : "none",
                gs::precision_name(o.precision), o.effects, o.model == gs::ContactModel::linear ? "linear" : "hertz",
                o.steps, o.step, scene.time_step, wall, rate, bytes, double(sim.device_bytes()) / n, t.integrate,
                t.neighbours, t.forces,
                contacts, sim.neighbour_builds(), double(gs::backend_reserved_peak_bytes(o.run.backend)) / n);
    if (o.digest) std::printf("state_digest=0x%016" PRIx64 "\n", gs::state_digest(sim.snapshot(), sim.history()));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "settle_bench: %s\n", e.what());
    return 1;
  }
}
