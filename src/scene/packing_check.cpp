#include "scene/packing_check.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "scene/generators.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/sphere_grid.hpp"

namespace gs {

using scene_yaml::str;

namespace {

// The overlap grid indexes its entries with 32-bit integers.
constexpr std::size_t kMaxGridSpheres = 200000000;

std::string describe(const ParticleInit& p) {
  return "particle " + std::to_string(p.id) + " at " + str(p.position) + " with radius " + str(p.radius);
}

// What keeps p from fitting the domain and the walls at t = 0; empty when it fits.
std::string misfit(const SceneSpec& s, const ParticleInit& p) {
  const double slack = kTouchTolerance * p.radius;
  const Vec3d& c = p.position;
  const Vec3d &lo = s.domain_min, &hi = s.domain_max;
  const double r = p.radius - slack;
  if (c.x - r < lo.x || c.y - r < lo.y || c.z - r < lo.z || c.x + r > hi.x || c.y + r > hi.y || c.z + r > hi.z)
    return describe(p) + " is not inside the domain " + str(lo) + " .. " + str(hi);
  for (std::size_t w = 0; w < s.walls.size(); ++w) {
    if (!timeline_of(s.wall_timelines, w).active.contains(0)) continue;  // not there at t = 0
    const double depth = wall_penetration(s.walls[w], c, p.radius);
    if (depth > slack)
      return describe(p) + " cuts " + str(depth) + " m into wall " + scene_yaml::quoted(s.wall_names[w]) +
             " at t = 0";
  }
  return "";
}

// The same test as the loader's overlap grid (SphereGrid::overlapping).
bool overlap(const ParticleInit& a, const ParticleInit& b) {
  const double reach = (a.radius + b.radius) * (1.0 - kTouchTolerance);
  return norm2(a.position - b.position) < reach * reach;
}

ParticleSetOrigin origin_of(const SceneSpec& s, std::size_t id) {
  if (s.set_origins.empty()) return {};  // a scene built in code: "scene"
  auto it = std::upper_bound(s.set_origins.begin(), s.set_origins.end(), id,
                             [](std::size_t i, const ParticleSetOrigin& o) { return i < o.first; });
  return it == s.set_origins.begin() ? *it : *std::prev(it);
}

// "<file>:<line>: <key>: <what>", as the loader words every error.
[[noreturn]] void fail_at(const SceneSpec& s, const ParticleSetOrigin& o, const std::string& what) {
  throw SceneError(s.path + ":" + std::to_string(o.line) + ": " +
                   (o.key.empty() ? "scene" : scene_yaml::cut(o.key, 2 * scene_yaml::kEchoLength)) + ": " + what);
}

ParticleInit particle(const SceneSpec& s, std::size_t id) {
  std::vector<ParticleInit> one;
  ParticleStream(s).generate(id, id + 1, one);
  return one.front();
}

}  // namespace

std::size_t first_misfit(const SceneSpec& scene, std::size_t first, std::size_t last) {
  return find_first(scene, first, last, [&scene](const ParticleInit& p) { return !misfit(scene, p).empty(); });
}

bool sets_may_overlap(const SceneSpec& s) {
  return !s.particles.empty() || s.lattices.size() + s.fills.size() > 1;
}

ParticleShare every_particle() {
  const double inf = std::numeric_limits<double>::infinity();
  return {nullptr, {Vec3d(-inf, -inf, -inf), Vec3d(inf, inf, inf)}};
}

// Every particle within reach of the share, in id order, goes into one grid;
// a particle of the share that overlaps one already in is an offence. A pair
// that overlaps lies within two largest radii, so the grown box holds the
// lower-id partner of every offence of the share.
std::size_t first_overlapping(const SceneSpec& s, const ParticleShare& share) {
  const std::size_t n = particle_count(s);
  const double reach = 2 * largest_radius(s);
  const Vec3d margin(reach, reach, reach);
  const KeepWindow near{share.window.lo - margin, share.window.hi + margin};
  const std::vector<ParticleInit> ps = select_particles(
      s,
      [&near](const Vec3d& x) {
        return x.x >= near.lo.x && x.y >= near.lo.y && x.z >= near.lo.z && x.x <= near.hi.x && x.y <= near.hi.y &&
               x.z <= near.hi.z;
      },
      near);
  if (ps.size() < 2) return n;
  if (ps.size() > kMaxGridSpheres)
    throw GenerateError("too many particles (" + std::to_string(ps.size()) + ") for the overlap check");
  Vec3d lo = ps[0].position, hi = ps[0].position;
  double mean_r = 0;
  for (const ParticleInit& p : ps) {
    lo = Vec3d(std::min(lo.x, p.position.x), std::min(lo.y, p.position.y), std::min(lo.z, p.position.z));
    hi = Vec3d(std::max(hi.x, p.position.x), std::max(hi.y, p.position.y), std::max(hi.z, p.position.z));
    mean_r += p.radius / double(ps.size());
  }
  SphereGrid grid(lo, hi, 2 * mean_r, ps.size());
  for (const ParticleInit& p : ps) {
    if ((!share.keep || share.keep(p.position)) && grid.overlapping(p.position, p.radius, kTouchTolerance) >= 0)
      return p.id;
    grid.insert(p.position, p.radius);
  }
  return n;
}

void report_misfit(const SceneSpec& s, std::size_t id) {
  const ParticleInit p = particle(s, id);
  fail_at(s, origin_of(s, id), misfit(s, p));
}

void report_overlap(const SceneSpec& s, std::size_t id) {
  const ParticleInit b = particle(s, id);
  const double reach = b.radius + largest_radius(s);
  const Vec3d r(reach, reach, reach);
  ParticleInit a;
  a.id = ParticleId(id);
  ParticleStream(s).for_each_near(id, b.position - r, b.position + r, [&](const ParticleInit& p) {
    if (p.id < a.id && overlap(p, b)) a = p;
  });
  const ParticleSetOrigin first = origin_of(s, a.id);
  fail_at(s, origin_of(s, id),
          describe(b) + " overlaps " + describe(a) + " (" + first.key + ", line " + std::to_string(first.line) + ")");
}

void report_generate_error(const SceneSpec& s, const std::exception& error) {
  const auto* g = dynamic_cast<const GenerateError*>(&error);
  const std::size_t set = g && g->set_first != GenerateError::kUnknown ? g->set_first : 0;
  fail_at(s, origin_of(s, set), error.what());
}

void check_packing(const SceneSpec& s) {
  const std::size_t n = particle_count(s);
  std::size_t bad = n;
  try {
    bad = first_misfit(s, 0, n);
    if (bad == n && sets_may_overlap(s)) {
      bad = first_overlapping(s, every_particle());
      if (bad < n) report_overlap(s, bad);
    }
  } catch (const GenerateError& e) {
    report_generate_error(s, e);
  }
  if (bad < n) report_misfit(s, bad);
}

}  // namespace gs
