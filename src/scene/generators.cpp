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
