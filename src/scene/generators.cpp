#include "scene/generators.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>

#include "scene/particle_sources.hpp"
#include "scene/sphere_grid.hpp"

namespace gs {

namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }

// Random sequential addition cannot pass random close packing; a request above
// it fails at once instead of after millions of futile trials.
constexpr double kMaxFillFraction = 0.64;

[[noreturn]] void too_full(std::size_t placed, std::size_t count, double fraction, const char* why) {
  std::ostringstream msg;
  msg << "the region is too full for the requested count: " << why << " (placed " << placed << " of "
      << count << " particles, requested solid fraction " << fraction
      << "); use a bigger region or fewer or smaller particles";
  throw GenerateError(msg.str());
}


// The two grids of a fill: exact overlap queries, and a fine bitmap of space
// no further centre can use, which rejects most doomed trials for one bit.
struct FillGrids {
  SphereGrid spheres;
  TakenCells taken;
  double r_min;  // smallest radius still to come: what a taken cell must refuse

  void insert(const Vec3d& c, double r) {
    spheres.insert(c, r);
    taken.take_ball(c, r + r_min);
  }

  // Spheres of earlier sets that reach into the box [lo, hi] are obstacles.
  void add_obstacles(const EarlierSpheres& earlier, const Vec3d& lo, const Vec3d& hi) {
    earlier([&](const ParticleInit& p) {
      const Vec3d& c = p.position;
      const double r = p.radius;
      if (c.x + r > lo.x && c.x - r < hi.x && c.y + r > lo.y && c.y - r < hi.y && c.z + r > lo.z && c.z - r < hi.z)
        insert(c, r);
    });
  }
};

// Cheap bitmap rejections allowed per overlap query before giving up: a fill
// close to jamming may reject many trials that way, but must still end.
constexpr long kDrawsPerAttempt = 200;

// Draws centres for a sphere of radius r until one is free; false after
// `max_attempts` overlap queries (or as many draws as that allows).
bool place(const FillRegion& reg, FillGrids& g, double r, int max_attempts, std::mt19937_64& rng, Vec3d& c) {
  int attempts = 0;
  for (long draws = 0; draws < kDrawsPerAttempt * max_attempts && attempts < max_attempts; ++draws) {
    if (!g.taken.sample(rng, c) || !admits(reg, c, r)) continue;
    ++attempts;
    if (g.spheres.overlapping(c, r, 0.0) < 0) return true;
  }
  return false;
}

constexpr std::size_t kMaxFillCount = 200000000;

}  // namespace

ParticleInit make_particle(const ParticleTemplate& t, std::size_t id, const Vec3d& pos, double r) {
  ParticleInit p;
  p.id = ParticleId(id);
  p.material = t.material;
  p.radius = r;
  p.position = pos;
  p.velocity = t.velocity;
  p.angular_velocity = t.angular_velocity;
  p.marker = t.marker;
  p.frozen = std::uint8_t(t.frozen);
  return p;
}

void check_id_room(std::size_t existing, std::size_t count) {
  if (count > std::size_t(kMaxParticleId) + 1 - std::min(existing, std::size_t(kMaxParticleId) + 1))
    throw GenerateError("too many particles: ids would exceed the 32-bit id range");
}

namespace {

// Sites along one axis in double: a huge extent gives a huge count here,
// where converting first would overflow (1e20 m gave one site).
double axis_sites(double lo, double hi, double spacing) {
  if (hi < lo) return 0;
  // The small slack keeps a site that sits exactly on `hi` despite rounding.
  return std::floor((hi - lo) / spacing + 1e-9) + 1;
}

// More sites than particle ids: refused before any count is converted.
void check_site_count(double sites) {
  if (!(sites <= double(kMaxParticleId) + 1)) {
    std::ostringstream msg;
    msg << "the lattice would have " << sites << " sites, more than the " << double(kMaxParticleId) + 1
        << " particle ids: check min, max and spacing";
    throw GenerateError(msg.str());
  }
}

}  // namespace

std::size_t lattice_sites(double lo, double hi, double spacing) {
  const double n = axis_sites(lo, hi, spacing);
  check_site_count(n);
  return std::size_t(n);
}

std::size_t lattice_count(const LatticeSpec& s) {
  const double n = axis_sites(s.min.x, s.max.x, s.spacing) * axis_sites(s.min.y, s.max.y, s.spacing) *
                   axis_sites(s.min.z, s.max.z, s.spacing);
  check_site_count(n);
  return std::size_t(n);
}

void generate_lattice(const LatticeSpec& s, std::vector<ParticleInit>& out) {
  check_id_room(out.size(), lattice_count(s));  // refuses before nx * ny * nz could overflow
  const LatticeSites sites(s, ParticleId(out.size()));
  out.reserve(out.size() + sites.count());
  for (std::size_t k = 0; k < sites.count(); ++k) out.push_back(sites.at(k));
}

std::vector<double> random_fill_radii(const SizeSpec& size, std::size_t count, std::uint64_t seed) {
  std::vector<double> radii;
  radii.reserve(count);
  if (size.kind == SizeSpec::Kind::fixed) {
    radii.assign(count, size.radius_min);
  } else if (size.kind == SizeSpec::Kind::uniform) {
    // A stream of its own, so the radii do not depend on how placement goes.
    std::mt19937_64 rng(seed ^ 0x9E3779B97F4A7C15ull);
    for (std::size_t i = 0; i < count; ++i) radii.push_back(radius_at(size, uniform01(rng)));
  } else {
    // Largest remainder: floor every share, then hand the leftover particles
    // to the classes with the largest fractional parts.
    const std::size_t n = size.classes.size();
    std::vector<std::size_t> share(n);
    std::vector<double> rest(n);
    std::size_t given = 0;
    for (std::size_t c = 0; c < n; ++c) {
      const double exact = size.classes[c].fraction * double(count);
      share[c] = std::size_t(std::floor(exact));
      rest[c] = exact - double(share[c]);
      given += share[c];
    }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rest[a] > rest[b]; });
    for (std::size_t k = 0; given < count; ++k, ++given) ++share[order[k % n]];
    for (std::size_t c = 0; c < n; ++c) radii.insert(radii.end(), share[c], 0.5 * size.classes[c].diameter);
  }
  // Largest first: big spheres are the hard ones to fit once small ones are in.
  std::sort(radii.begin(), radii.end(), std::greater<double>());
  return radii;
}

void generate_random_fill(const RandomFillSpec& s, std::vector<ParticleInit>& out) {
  // The earlier spheres are visited before any is appended, so `out` is stable meanwhile.
  const std::size_t first_id = out.size();
  const EarlierSpheres earlier = [&out, first_id](const SphereVisitor& visit) {
    for (std::size_t i = 0; i < first_id; ++i) visit(out[i]);
  };
  generate_random_fill(s, earlier, first_id, out);
}

void generate_random_fill(const RandomFillSpec& s, const EarlierSpheres& earlier, std::size_t first_id,
                          std::vector<ParticleInit>& out) {
  check_id_room(first_id, s.count);
  if (s.count == 0) return;
  // The grids index their entries with 32-bit integers.
  if (s.count > kMaxFillCount)
    throw GenerateError("a random fill places at most " + std::to_string(kMaxFillCount) + " particles; split it");
  const std::vector<double> radii = random_fill_radii(s.size, s.count, s.seed);
  const double r_min = radii.back();
  if (!fits(s.region, radii.front()))
    throw GenerateError("the region is smaller than one particle of radius " + std::to_string(radii.front()));
  double solid = 0, mean_r = 0;
  for (double r : radii) {
    solid += sphere_volume(r);
    mean_r += r / double(s.count);
  }
  const double fraction = solid / region_volume(s.region);
  if (fraction > kMaxFillFraction) too_full(0, s.count, fraction, "denser than random close packing");

  // Trials are drawn in the box of the centres of the smallest spheres.
  Vec3d lo, hi, centre_lo, centre_hi;
  region_bounds(s.region, lo, hi);
  region_bounds(shrunk(s.region, r_min), centre_lo, centre_hi);
  // Overlap cells of one mean diameter were fastest in trials; taken cells of
  // r_min / 2 let a sphere's exclusion ball cover whole cells (8 bytes per particle at most).
  FillGrids g{SphereGrid(lo, hi, 2 * mean_r, s.count),
              TakenCells(centre_lo, centre_hi, 0.5 * r_min, 64.0 * double(s.count) + 65536.0), r_min};
  g.add_obstacles(earlier, lo, hi);

  std::mt19937_64 rng(s.seed);
  out.reserve(out.size() + s.count);
  for (std::size_t i = 0; i < s.count; ++i) {
    Vec3d c;
    if (!place(s.region, g, radii[i], s.max_attempts, rng, c))
      too_full(i, s.count, fraction, "no free spot found for a particle");
    g.insert(c, radii[i]);
    out.push_back(make_particle(s.tmpl, first_id + i, c, radii[i]));
  }
}

bool find_overlap(const std::vector<ParticleInit>& ps, std::size_t& first, std::size_t& second, double tol) {
  if (ps.size() < 2) return false;
  if (ps.size() > kMaxFillCount)
    throw GenerateError("too many particles (" + std::to_string(ps.size()) + ") for the overlap check");
  Vec3d lo = ps[0].position, hi = ps[0].position;
  double mean_r = 0;
  for (const ParticleInit& p : ps) {
    const Vec3d& c = p.position;
    lo = Vec3d(std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z));
    hi = Vec3d(std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z));
    mean_r += p.radius;
  }
  mean_r /= double(ps.size());
  SphereGrid grid(lo, hi, 2 * mean_r, ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const long j = grid.overlapping(ps[i].position, ps[i].radius, tol);
    if (j >= 0) {
      first = std::size_t(j);
      second = i;
      return true;
    }
    grid.insert(ps[i].position, ps[i].radius);
  }
  return false;
}

}  // namespace gs
