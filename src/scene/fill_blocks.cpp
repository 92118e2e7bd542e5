#include "scene/fill_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include "scene/counter_random.hpp"
#include "scene/sphere_grid.hpp"

namespace gs {
namespace {

// Counter streams of a fill: radii and each block's placement draw apart.
constexpr std::uint64_t kRadiusStream = 0x7261646969ull, kPlacementStream = 0x706c616365ull;

// Random sequential addition cannot pass random close packing; a request above
// it fails at once instead of after millions of futile trials.
constexpr double kMaxFillFraction = 0.64;

// The grids index their entries with 32-bit integers.
constexpr std::size_t kMaxBlockCount = 200000000;

double& axis(Vec3d& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }
double axis(const Vec3d& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

double solid_fraction(const RandomFillSpec& s) {
  return mean_particle_volume(s.size) * double(s.count) / region_volume(s.region);
}

[[noreturn]] void too_full(const RandomFillSpec& s, std::size_t first_id, std::size_t placed, std::size_t count,
                           const std::string& why) {
  std::ostringstream msg;
  msg << "the region is too full for the requested count: " << why << " (placed " << placed << " of " << count
      << " particles, requested solid fraction " << solid_fraction(s)
      << "); use a bigger region or fewer or smaller particles";
  throw GenerateError(msg.str(), first_id);
}

// The box whose centres keep a sphere of radius r inside the block: faces
// inside the region move in by r, faces on the region's bounds stay (the
// region itself keeps the spheres in there).
void centre_box(const FillBlocks& blocks, std::size_t b, double r, Vec3d& lo, Vec3d& hi) {
  block_box(blocks, b, lo, hi);
  const std::size_t i[3] = {b % std::size_t(blocks.n[0]), b / std::size_t(blocks.n[0]) % std::size_t(blocks.n[1]),
                            b / (std::size_t(blocks.n[0]) * std::size_t(blocks.n[1]))};
  for (int a = 0; a < 3; ++a) {
    if (i[a] > 0) axis(lo, a) += r;
    if (i[a] + 1 < std::size_t(blocks.n[a])) axis(hi, a) -= r;
  }
}

bool inside(const Vec3d& p, const Vec3d& lo, const Vec3d& hi) {
  return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}

// Volume of the centres block b may give a largest sphere: its centre box
// within the region shrunk by the largest radius. Whole when all eight
// corners are in (both shapes are convex), else a midpoint rule on 32^3 points
// of the box clipped to the shrunk region's bounds.
double usable_volume(const RandomFillSpec& s, const FillBlocks& blocks, std::size_t b, double r) {
  Vec3d lo, hi, fit_lo, fit_hi;
  centre_box(blocks, b, r, lo, hi);
  // Within the bounds of the centres that fit: exact for a box region, and a
  // region barely thicker than a sphere is not missed between the points.
  region_bounds(shrunk(s.region, r), fit_lo, fit_hi);
  for (int a = 0; a < 3; ++a) {
    axis(lo, a) = std::max(axis(lo, a), axis(fit_lo, a));
    axis(hi, a) = std::min(axis(hi, a), axis(fit_hi, a));
  }
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return 0;
  const Vec3d d = hi - lo;
  // A region exactly one sphere thick along an axis (every block alike) is
  // measured across the others.
  const double measure = (d.x > 0 ? d.x : 1) * (d.y > 0 ? d.y : 1) * (d.z > 0 ? d.z : 1);
  bool all = true;
  for (int c = 0; c < 8 && all; ++c)
    all = admits(s.region, Vec3d(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z), r);
  if (all) return measure;
  constexpr int k = 32;
  long in = 0;
  for (int z = 0; z < k; ++z)
    for (int y = 0; y < k; ++y)
      for (int x = 0; x < k; ++x)
        in += admits(s.region, lo + Vec3d(d.x * (x + 0.5) / k, d.y * (y + 0.5) / k, d.z * (z + 0.5) / k), r);
  return measure * double(in) / (k * k * k);
}

// nx × ny × nz: blocks at least kFillBlockDiameters wide, and no more of them
// than leaves kFillBlockMinCount particles to each on average.
void choose_layout(const RandomFillSpec& s, FillBlocks& blocks) {
  region_bounds(s.region, blocks.lo, blocks.hi);
  const double width = kFillBlockDiameters * 2 * largest_radius(s.size);
  const double most = std::max(1.0, std::floor(double(s.count) / double(kFillBlockMinCount)));
  for (int a = 0; a < 3; ++a)
    blocks.n[a] = int(std::clamp(std::floor((axis(blocks.hi, a) - axis(blocks.lo, a)) / width), 1.0, 1024.0));
  while (double(blocks.n[0]) * blocks.n[1] * blocks.n[2] > most) {
    int* widest = std::max_element(blocks.n, blocks.n + 3);
    *widest = (*widest + 1) / 2;
  }
}

// Each block's share of the count by the largest-remainder method over the
// usable volumes (ties to the lower block), as prefix sums.
void share_count(const RandomFillSpec& s, FillBlocks& blocks) {
  const std::size_t n = std::size_t(blocks.n[0]) * blocks.n[1] * blocks.n[2];
  const double r = largest_radius(s.size);
  std::vector<double> volume(n);
#pragma omp parallel for schedule(dynamic)
  for (long b = 0; b < long(n); ++b) volume[std::size_t(b)] = usable_volume(s, blocks, std::size_t(b), r);
  const double total = std::accumulate(volume.begin(), volume.end(), 0.0);
  if (!(total > 0)) throw GenerateError("no block of the region has room for a particle of radius " + std::to_string(r));
  std::vector<std::size_t> share(n);
  std::vector<double> rest(n);
  std::size_t given = 0;
  for (std::size_t b = 0; b < n; ++b) {
    const double exact = volume[b] / total * double(s.count);
    share[b] = std::min(s.count - given, std::size_t(std::floor(exact)));
    rest[b] = exact - double(share[b]);
    given += share[b];
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rest[a] > rest[b]; });
  for (std::size_t k = 0; given < s.count; ++k, ++given) ++share[order[k % n]];
  blocks.start.assign(n + 1, 0);
  for (std::size_t b = 0; b < n; ++b) blocks.start[b + 1] = blocks.start[b] + share[b];
}

// Radii of the fill's particles first .. first + n - 1, largest first:
// uniform radii drawn one counter each, classes split within the block.
std::vector<double> block_radii(const RandomFillSpec& s, std::size_t first, std::size_t n) {
  if (s.size.kind != SizeSpec::Kind::uniform) return random_fill_radii(s.size, n, s.seed);
  std::vector<double> radii(n);
  for (std::size_t k = 0; k < n; ++k) radii[k] = radius_at(s.size, counter_uniform(s.seed, kRadiusStream, first + k, 0));
  std::sort(radii.begin(), radii.end(), std::greater<double>());
  return radii;
}

// The two grids of a block: exact overlap queries, and a fine bitmap of space
// no further centre can use, which rejects most doomed trials for one bit.
struct FillGrids {
  SphereGrid spheres;
  TakenCells taken;
  double r_min;  // smallest radius still to come: what a taken cell must refuse

  void insert(const Vec3d& c, double r) {
    spheres.insert(c, r);
    taken.take_ball(c, r + r_min);
  }
};

// Cheap bitmap rejections allowed per overlap query before giving up: a fill
// close to jamming may reject many trials that way, but must still end.
constexpr long kDrawsPerAttempt = 200;

// Where a centre may go: in the region and in the block's centre box.
struct Room {
  const FillRegion& region;
  Vec3d lo, hi;
  bool admits(const Vec3d& c, double r) const { return inside(c, lo, hi) && gs::admits(region, c, r); }
};

// Draws centres for a sphere of radius r until one is free; false after
// `max_attempts` overlap queries (or as many draws as that allows).
bool place(const Room& room, FillGrids& g, double r, int max_attempts, std::mt19937_64& rng, Vec3d& c) {
  int attempts = 0;
  for (long draws = 0; draws < kDrawsPerAttempt * max_attempts && attempts < max_attempts; ++draws) {
    if (!g.taken.sample(rng, c) || !room.admits(c, r)) continue;
    ++attempts;
    if (g.spheres.overlapping(c, r, 0.0) < 0) return true;
  }
  return false;
}

}  // namespace

void check_random_fill(const RandomFillSpec& s, std::size_t first_id) {
  check_id_room(first_id, s.count);
  const double r = largest_radius(s.size);
  if (!fits(s.region, r)) throw GenerateError("the region is smaller than one particle of radius " + std::to_string(r));
  if (solid_fraction(s) > kMaxFillFraction) too_full(s, first_id, 0, s.count, "denser than random close packing");
}

RandomFillSource make_fill_source(const RandomFillSpec& spec, std::size_t first_id) {
  check_random_fill(spec, first_id);
  RandomFillSource f{spec, ParticleId(first_id), spec.count, {}};
  choose_layout(spec, f.blocks);
  share_count(spec, f.blocks);
  return f;
}

void block_box(const FillBlocks& blocks, std::size_t b, Vec3d& lo, Vec3d& hi) {
  const std::size_t i[3] = {b % std::size_t(blocks.n[0]), b / std::size_t(blocks.n[0]) % std::size_t(blocks.n[1]),
                            b / (std::size_t(blocks.n[0]) * std::size_t(blocks.n[1]))};
  for (int a = 0; a < 3; ++a) {
    // The same expression for a face seen from either side, so neighbours agree bitwise.
    const double span = axis(blocks.hi, a) - axis(blocks.lo, a);
    axis(lo, a) = axis(blocks.lo, a) + span * double(i[a]) / blocks.n[a];
    axis(hi, a) = i[a] + 1 == std::size_t(blocks.n[a]) ? axis(blocks.hi, a) : axis(blocks.lo, a) + span * double(i[a] + 1) / blocks.n[a];
  }
}

std::size_t block_of(const FillBlocks& blocks, std::size_t index) {
  return std::size_t(std::upper_bound(blocks.start.begin(), blocks.start.end(), index) - blocks.start.begin()) - 1;
}

std::vector<std::size_t> blocks_meeting(const FillBlocks& blocks, const Vec3d& lo, const Vec3d& hi) {
  int from[3], to[3];
  for (int a = 0; a < 3; ++a) {
    const double scale = blocks.n[a] / (axis(blocks.hi, a) - axis(blocks.lo, a));
    // One block of slack each way against rounding; the exact test follows.
    from[a] = int(std::clamp(std::floor((axis(lo, a) - axis(blocks.lo, a)) * scale) - 1, 0.0, double(blocks.n[a] - 1)));
    to[a] = int(std::clamp(std::floor((axis(hi, a) - axis(blocks.lo, a)) * scale) + 1, 0.0, double(blocks.n[a] - 1)));
  }
  std::vector<std::size_t> out;
  for (int z = from[2]; z <= to[2]; ++z)
    for (int y = from[1]; y <= to[1]; ++y)
      for (int x = from[0]; x <= to[0]; ++x) {
        const std::size_t b = (std::size_t(z) * blocks.n[1] + std::size_t(y)) * blocks.n[0] + std::size_t(x);
        Vec3d blo, bhi;
        block_box(blocks, b, blo, bhi);
        if (blo.x <= hi.x && blo.y <= hi.y && blo.z <= hi.z && bhi.x >= lo.x && bhi.y >= lo.y && bhi.z >= lo.z)
          out.push_back(b);
      }
  return out;
}

void generate_fill_block(const RandomFillSource& f, std::size_t b, const SpheresNear& earlier,
                         std::vector<ParticleInit>& out) {
  const RandomFillSpec& s = f.spec;
  const std::size_t first = f.blocks.start[b], n = f.blocks.start[b + 1] - first;
  if (n == 0) return;
  if (n > kMaxBlockCount)
    throw GenerateError("a block of a random fill holds at most " + std::to_string(kMaxBlockCount) +
                        " particles; use fewer small particles per large one", f.first_id);
  const std::vector<double> radii = block_radii(s, first, n);
  const double r_max = largest_radius(s.size), r_min = radii.back();
  double mean_r = 0;
  for (double r : radii) mean_r += r / double(n);
  Vec3d lo, hi, region_lo, region_hi;
  block_box(f.blocks, b, lo, hi);
  Room room{s.region, {}, {}};
  centre_box(f.blocks, b, r_max, room.lo, room.hi);
  // Trials are drawn where the smallest sphere's centre may go.
  region_bounds(shrunk(s.region, r_min), region_lo, region_hi);
  for (int a = 0; a < 3; ++a) {
    axis(room.lo, a) = std::max(axis(room.lo, a), axis(region_lo, a));
    axis(room.hi, a) = std::min(axis(room.hi, a), axis(region_hi, a));
  }
  if (!(room.lo.x <= room.hi.x && room.lo.y <= room.hi.y && room.lo.z <= room.hi.z))
    too_full(s, f.first_id, 0, n, "a block of the fill has no room for its particles");
  // Overlap cells of one mean diameter were fastest in trials; taken cells of
  // r_min / 2 let a sphere's exclusion ball cover whole cells (8 bytes per particle at most).
  FillGrids g{SphereGrid(lo, hi, 2 * mean_r, n), TakenCells(room.lo, room.hi, 0.5 * r_min, 64.0 * double(n) + 65536.0),
              r_min};
  earlier(lo, hi, [&g](const ParticleInit& p) { g.insert(p.position, p.radius); });
  std::mt19937_64 rng(counter_hash(s.seed, kPlacementStream, b, 0));
  out.reserve(out.size() + n);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3d c;
    if (!place(room, g, radii[i], s.max_attempts, rng, c))
      too_full(s, f.first_id, i, n, "no free spot found for a particle in block " + std::to_string(b));
    g.insert(c, radii[i]);
    out.push_back(make_particle(s.tmpl, f.first_id + first + i, c, radii[i]));
  }
}

// The serial entry points: every block in order, around the earlier spheres.
void generate_random_fill(const RandomFillSpec& s, const EarlierSpheres& earlier, std::size_t first_id,
                          std::vector<ParticleInit>& out) {
  if (s.count == 0) {
    check_id_room(first_id, 0);
    return;
  }
  const RandomFillSource f = make_fill_source(s, first_id);
  std::vector<ParticleInit> obstacles;
  earlier([&obstacles](const ParticleInit& p) { obstacles.push_back(p); });
  const SpheresNear near = [&obstacles](const Vec3d& lo, const Vec3d& hi, const SphereVisitor& visit) {
    for (const ParticleInit& p : obstacles) {
      const Vec3d r(p.radius, p.radius, p.radius);
      if (inside(p.position, lo - r, hi + r)) visit(p);
    }
  };
  for (std::size_t b = 0; b < f.blocks.count(); ++b) generate_fill_block(f, b, near, out);
}

void generate_random_fill(const RandomFillSpec& s, std::vector<ParticleInit>& out) {
  // The earlier spheres are visited before any is appended, so `out` is stable meanwhile.
  const std::size_t first_id = out.size();
  const EarlierSpheres earlier = [&out, first_id](const SphereVisitor& visit) {
    for (std::size_t i = 0; i < first_id; ++i) visit(out[i]);
  };
  generate_random_fill(s, earlier, first_id, out);
}

}  // namespace gs
