#pragma once
// Shared checks of the stability suite (docs/STABILITY.md): the health of a
// snapshot (finite state, particles conserved and inside the domain and the
// walls), the deepest overlap found on the host, and the total energy.
// Header only: each tests/stability/test_*.cpp is its own binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <unordered_map>
#include <vector>

#include "scene/scene_time_step.hpp"
#include "scene/generators.hpp"
#include "support/support.hpp"
#include "walls/wall_geometry.hpp"

namespace gs::test {

// GS_STABILITY_LONG=1 selects the long variant of every case (more particles
// and steps, meant for a GPU: GS_STABILITY_LONG=1 GS_TEST_BACKENDS=cuda ctest -R Stability).
inline bool stability_long() {
  const char* env = std::getenv("GS_STABILITY_LONG");
  return env && std::strcmp(env, "0") != 0 && env[0] != '\0';
}

template <class T>
T short_or_long(T short_value, T long_value) {
  return stability_long() ? long_value : short_value;
}

// GS_STABILITY_STEP_FACTOR=f runs every case at f times the largest accepted
// step, to see the suite fail above the limit (docs/STABILITY.md).
inline double step_factor() {
  const char* env = std::getenv("GS_STABILITY_STEP_FACTOR");
  return env && env[0] != '\0' ? std::atof(env) : 1.0;
}

// The largest step the scene loader accepts for this scene
// (contact/stable_step.hpp), with the contact time it is measured against.
inline void set_largest_accepted_step(SceneSpec& scene) {
  scene.contact_time = critical_contact_time(scene);
  const StableStep limit = stable_time_step(scene);
  scene.stable_time_step = limit.time_step;
  scene.stable_step_binding = limit.binding;
  scene.time_step = step_factor() * limit.time_step;
}

// Deepest overlaps in a snapshot, relative to a radius.
struct Overlaps {
  double particle = 0;  // max over pairs of overlap / smaller radius
  double wall = 0;      // max over spheres and walls of overlap / radius
  double worst() const { return std::max(particle, wall); }
};

// Every overlapping pair, found by binning the centres into cells of the
// smallest diameter: each pair is searched from its larger sphere (to the
// reach of twice that radius), so small spheres look only at their 27 cells
// and the cost stays near O(N) for any size ratio. Walls at their current pose.
inline Overlaps max_overlaps(const ParticleSnapshot& s, const std::vector<Wall>& walls) {
  Overlaps out;
  const std::size_t n = s.size();
  if (n == 0) return out;
  const double cell = 2.0 * double(*std::min_element(s.radius.begin(), s.radius.end()));
  Vec3d lo = s.position[0];
  for (const Vec3d& x : s.position) lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
  auto coordinate = [&](double x, double origin) { return std::int64_t(std::floor((x - origin) / cell)); };
  auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) { return (i << 42) ^ (j << 21) ^ k; };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> bins;
  for (std::size_t i = 0; i < n; ++i)
    bins[key(coordinate(s.position[i].x, lo.x), coordinate(s.position[i].y, lo.y),
             coordinate(s.position[i].z, lo.z))].push_back(i);
  for (std::size_t i = 0; i < n; ++i) {
    const double ri = s.radius[i];
    const std::int64_t reach = std::int64_t(std::ceil(2.0 * ri / cell));
    const Vec3d& xi = s.position[i];
    const std::int64_t ci = coordinate(xi.x, lo.x), cj = coordinate(xi.y, lo.y), ck = coordinate(xi.z, lo.z);
    for (std::int64_t a = ci - reach; a <= ci + reach; ++a)
      for (std::int64_t b = cj - reach; b <= cj + reach; ++b)
        for (std::int64_t c = ck - reach; c <= ck + reach; ++c) {
          const auto bin = bins.find(key(a, b, c));
          if (bin == bins.end()) continue;
          for (std::size_t j : bin->second) {
            const double rj = s.radius[j];
            if (rj > ri || (rj == ri && j <= i)) continue;  // searched from the larger one
            const double overlap = ri + rj - norm(xi - s.position[j]);
            if (overlap > 0) out.particle = std::max(out.particle, overlap / rj);
          }
        }
    for (const Wall& w : walls) {
      WallContact contact;
      if (wall_contact(w, xi, ri, contact)) out.wall = std::max(out.wall, contact.overlap / ri);
    }
  }
  return out;
}

// Kinetic (translation and rotation) plus gravitational potential energy,
// the potential measured from `reference` (so a bed far from the origin
// keeps its significant digits).
inline double mechanical_energy(const ParticleSnapshot& s, const Vec3d& gravity, const Vec3d& reference = {}) {
  double e = kinetic_energy(s);
  for (std::size_t i = 0; i < s.size(); ++i) e -= double(s.mass[i]) * dot(gravity, s.position[i] - reference);
  return e;
}

inline double max_speed(const ParticleSnapshot& s) {
  double v = 0;
  for (const Vec3d& u : s.velocity) v = std::max(v, norm(u));
  return v;
}

// Signed distance of a point in front of a plane wall at its current pose.
inline double plane_distance(const Wall& w, const Vec3d& x) {
  return dot(x - wall_to_world(w, w.point), wall_rotate(w, w.normal));
}

// The state is finite, the ids are those of the scene (none lost, none
// duplicated) and every centre lies inside the domain and in front of every
// plane wall (a centre behind a wall has passed through it). Returns the
// number of failures so a caller can stop sampling after the first.
inline int expect_healthy(const ParticleSnapshot& s, const SceneSpec& scene, const std::vector<Wall>& walls) {
  int failures = 0;
  auto fail = [&](const std::string& what) {
    if (failures++ < 5) ADD_FAILURE() << "step " << s.step << ": " << what;
  };
  if (s.size() != scene.particles.size())
    fail("particle count " + std::to_string(s.size()) + ", expected " + std::to_string(scene.particles.size()));
  std::vector<ParticleId> expected;
  for (const ParticleInit& p : scene.particles) expected.push_back(p.id);
  std::sort(expected.begin(), expected.end());
  if (s.id != expected) fail("particle ids differ from the scene's");
  auto finite = [](const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3d& x = s.position[i];
    const std::string who = "particle " + std::to_string(s.id[i]);
    if (!finite(x) || !finite(s.velocity[i]) || !finite(s.angular_velocity[i])) fail(who + ": not finite");
    if (x.x < scene.domain_min.x || x.y < scene.domain_min.y || x.z < scene.domain_min.z ||
        x.x > scene.domain_max.x || x.y > scene.domain_max.y || x.z > scene.domain_max.z)
      fail(who + ": outside the domain");
    for (std::size_t w = 0; w < walls.size(); ++w)
      if (walls[w].kind == WallKind::plane && !(plane_distance(walls[w], x) > 0))
        fail(who + ": behind wall " + std::to_string(w));
  }
  return failures;
}

// A closed box of six plane walls facing inwards over [lo, hi].
inline std::vector<Wall> box_walls(const Vec3d& lo, const Vec3d& hi, int material = 0) {
  return {plane_wall(lo, {1, 0, 0}, material), plane_wall(hi, {-1, 0, 0}, material),
          plane_wall(lo, {0, 1, 0}, material), plane_wall(hi, {0, -1, 0}, material),
          plane_wall(lo, {0, 0, 1}, material), plane_wall(hi, {0, 0, -1}, material)};
}

// Appends `count` non-overlapping spheres of radius in [r_min, r_max] at
// random in [lo, hi] (centres and surfaces inside), ids continuing.
inline void add_random_fill(SceneSpec& scene, int material, std::size_t count, double r_min, double r_max,
                            const Vec3d& lo, const Vec3d& hi, std::uint64_t seed) {
  RandomFillSpec fill;
  fill.tmpl.material = material;
  fill.region.min = lo;
  fill.region.max = hi;
  fill.count = count;
  fill.size.kind = r_min == r_max ? SizeSpec::Kind::fixed : SizeSpec::Kind::uniform;
  fill.size.radius_min = r_min;
  fill.size.radius_max = r_max;
  fill.seed = seed;
  generate_random_fill(fill, scene.particles);
}

// Adds a material and its pairs with every material already present, all
// with the stiffness, restitution and friction of pair 0.
inline int add_material(SceneSpec& scene, const std::string& name, double density) {
  MaterialSpec m = scene.materials[0];
  m.name = name;
  m.density = density;
  scene.materials.push_back(m);
  const int index = int(scene.materials.size()) - 1;
  for (int other = 0; other <= index; ++other) {
    PairSpec p = scene.pairs[0];
    p.material_a = other;
    p.material_b = index;
    scene.pairs.push_back(p);
  }
  return index;
}

// Worst values seen while sampling a run.
struct RunRecord {
  double energy_growth = -std::numeric_limits<double>::infinity();  // max (E - E0) / scale
  Overlaps overlap;
  double speed = 0;
  int failures = 0;
};

// Runs `samples` chunks of `steps_per_sample` steps, checking health, the
// energy (relative to `energy_scale`, against the initial energy) and the
// overlaps after each.
inline RunRecord run_and_watch(Simulation& sim, int samples, long long steps_per_sample, double energy_scale,
                               const Vec3d& energy_reference = {}) {
  // The simulation keeps its scene without the particles (they are in its
  // store): the ids to expect are those it starts with.
  SceneSpec scene = sim.scene();
  const ParticleSnapshot start = sim.snapshot();
  for (ParticleId id : start.id) scene.particles.push_back(ParticleInit{id, 0, 0, {}, {}, {}, 0});
  RunRecord r;
  const double e0 = mechanical_energy(start, scene.gravity, energy_reference);
  for (int k = 0; k < samples && r.failures == 0; ++k) {
    sim.run(steps_per_sample);
    const ParticleSnapshot s = sim.snapshot();
    r.failures += expect_healthy(s, scene, sim.walls());
    r.energy_growth =
        std::max(r.energy_growth, (mechanical_energy(s, scene.gravity, energy_reference) - e0) / energy_scale);
    const Overlaps o = max_overlaps(s, sim.walls());
    r.overlap.particle = std::max(r.overlap.particle, o.particle);
    r.overlap.wall = std::max(r.overlap.wall, o.wall);
    r.speed = std::max(r.speed, max_speed(s));
  }
  return r;
}

}  // namespace gs::test
