#include "scene/particle_sources.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "scene/fill_blocks.hpp"
#include "scene/generators.hpp"
#include "scene/kept_fill_blocks.hpp"

namespace gs {

LatticeSites::LatticeSites(const LatticeSpec& spec, ParticleId first_id)
    : spec_(spec),
      first_id_(first_id),
      nx_(lattice_sites(spec.min.x, spec.max.x, spec.spacing)),
      ny_(lattice_sites(spec.min.y, spec.max.y, spec.spacing)),
      nz_(lattice_sites(spec.min.z, spec.max.z, spec.spacing)) {}

ParticleInit LatticeSites::at(std::size_t site) const {
  const std::size_t i = site % nx_, j = (site / nx_) % ny_, k = site / (nx_ * ny_);
  // The serial generator's expression, so the bits are its bits.
  const Vec3d position = spec_.min + spec_.spacing * Vec3d(double(i), double(j), double(k));
  return make_particle(spec_.tmpl, first_id_ + site, position, spec_.radius);
}

namespace {

// Does a sphere at c of radius r reach into the box [lo, hi]?
bool reaches(const Vec3d& c, double r, const Vec3d& lo, const Vec3d& hi) {
  return c.x + r >= lo.x && c.x - r <= hi.x && c.y + r >= lo.y && c.y - r <= hi.y && c.z + r >= lo.z &&
         c.z - r <= hi.z;
}

// Sites [from, to] along one axis whose sphere can reach [lo, hi] (one site
// of slack each way; the caller tests exactly); false when none.
bool site_range(double min, double spacing, std::size_t n, double lo, double hi, std::size_t& from, std::size_t& to) {
  const double a = std::floor((lo - min) / spacing) - 1, b = std::floor((hi - min) / spacing) + 1;
  if (b < 0 || a > double(n - 1)) return false;
  from = std::size_t(std::max(a, 0.0));
  to = std::size_t(std::min(b, double(n - 1)));
  return true;
}

// Blocks of fill generation kept for the next caller: enough for every thread's
// neighbours in id order.
constexpr std::size_t kCachedBlocks = 64;

}  // namespace

void LatticeSites::for_each_near(const Vec3d& lo, const Vec3d& hi,
                                 const std::function<void(const ParticleInit&)>& visit) const {
  const double r = spec_.radius, h = spec_.spacing;
  std::size_t i0, i1, j0, j1, k0, k1;
  if (!site_range(spec_.min.x, h, nx_, lo.x - r, hi.x + r, i0, i1) ||
      !site_range(spec_.min.y, h, ny_, lo.y - r, hi.y + r, j0, j1) ||
      !site_range(spec_.min.z, h, nz_, lo.z - r, hi.z + r, k0, k1))
    return;
  for (std::size_t k = k0; k <= k1; ++k)
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) {
        const ParticleInit p = at((k * ny_ + j) * nx_ + i);
        if (reaches(p.position, p.radius, lo, hi)) visit(p);
      }
}

ParticleStream::ParticleStream(const SceneSpec& scene) : scene_(scene) {
  const std::vector<ParticleInit>& listed = scene.particles;
  // The generated sets in id order, each after the listed particles before it.
  std::vector<Segment> sets;
  for (const LatticeSource& l : scene.lattices) sets.push_back({&l, nullptr, 0, l.first_id, l.count});
  for (const RandomFillSource& f : scene.fills) sets.push_back({nullptr, &f, 0, f.first_id, f.count});
  std::stable_sort(sets.begin(), sets.end(), [](const Segment& a, const Segment& b) { return a.begin < b.begin; });
  std::size_t e = 0;
  auto add = [&](Segment seg) {
    if (seg.count == 0) return;
    seg.begin = count_;
    segments_.push_back(seg);
    count_ += seg.count;
  };
  for (const Segment& set : sets) {
    const std::size_t run = e;
    while (e < listed.size() && listed[e].id < set.begin) ++e;
    add({nullptr, nullptr, run, 0, e - run});
    add(set);
  }
  add({nullptr, nullptr, e, 0, listed.size() - e});
  for (const LatticeSource& l : scene.lattices) sites_.emplace_back(l.spec, l.first_id);
}

ParticleStream::ParticleStream(const SceneSpec& scene, const Vec3d& lo, const Vec3d& hi) : ParticleStream(scene) {
  windowed_ = true;
  window_lo_ = lo;
  window_hi_ = hi;
}

bool ParticleStream::in_window(const RandomFillSource& fill, std::size_t b) const {
  if (!windowed_) return true;
  Vec3d lo, hi;
  block_box(fill.blocks, b, lo, hi);  // a block's centres lie in its box
  return lo.x <= window_hi_.x && lo.y <= window_hi_.y && lo.z <= window_hi_.z && hi.x >= window_lo_.x &&
         hi.y >= window_lo_.y && hi.z >= window_lo_.z;
}

ParticleStream::Block ParticleStream::fill_block(const RandomFillSource& fill, std::size_t b) const {
  {
    const std::lock_guard<std::mutex> lock(cache_mutex_);
    for (const CachedBlock& c : cache_)
      if (c.fill == &fill && c.block == b) return c.particles;
  }
  const std::size_t which = std::size_t(&fill - scene_.fills.data());
  KeptFillBlocks* kept = scene_.kept_blocks.get();
  if (kept)
    if (Block found = kept->find(which, b)) return found;
  // Made outside the lock: another thread may make the same block meanwhile, with the same bits.
  auto made = std::make_shared<std::vector<ParticleInit>>();
  const SpheresNear earlier = [this, &fill](const Vec3d& lo, const Vec3d& hi, const SphereVisitor& visit) {
    for_each_near(fill.first_id, lo, hi, visit);
  };
  generate_fill_block(fill, b, earlier, *made);
  if (kept) {
    Vec3d lo, hi;
    block_box(fill.blocks, b, lo, hi);
    kept->offer(which, b, lo, hi, made);
  }
  const std::lock_guard<std::mutex> lock(cache_mutex_);
  if (cache_.size() < kCachedBlocks) cache_.push_back({&fill, b, made});
  else cache_[cache_next_++ % kCachedBlocks] = {&fill, b, made};
  return made;
}

void ParticleStream::generate(std::size_t first, std::size_t last, std::vector<ParticleInit>& out) const {
  last = std::min(last, count_);
  if (first >= last) return;
  auto seg = std::upper_bound(segments_.begin(), segments_.end(), first,
                              [](std::size_t i, const Segment& s) { return i < s.begin; });
  for (--seg; first < last && seg != segments_.end(); ++seg) {
    const std::size_t from = first - seg->begin, to = std::min(last - seg->begin, seg->count);
    if (seg->lattice) {
      const LatticeSites& sites = sites_[std::size_t(seg->lattice - scene_.lattices.data())];
      for (std::size_t k = from; k < to; ++k) out.push_back(sites.at(k));
    } else if (seg->fill) {
      const FillBlocks& blocks = seg->fill->blocks;
      for (std::size_t b = block_of(blocks, from); b < blocks.count() && blocks.start[b] < to; ++b) {
        if (!in_window(*seg->fill, b)) continue;
        const Block made = fill_block(*seg->fill, b);
        const std::size_t s0 = blocks.start[b];
        const auto begin = made->begin() - std::ptrdiff_t(s0);
        out.insert(out.end(), begin + std::ptrdiff_t(std::max(from, s0)),
                   begin + std::ptrdiff_t(std::min(to, blocks.start[b + 1])));
      }
    } else {
      const auto begin = scene_.particles.begin() + std::ptrdiff_t(seg->offset);
      out.insert(out.end(), begin + std::ptrdiff_t(from), begin + std::ptrdiff_t(to));
    }
    first = seg->begin + to;
  }
}

void ParticleStream::for_each_near(std::size_t before, const Vec3d& lo, const Vec3d& hi,
                                   const std::function<void(const ParticleInit&)>& visit) const {
  for (const Segment& seg : segments_) {
    if (seg.begin >= before) break;
    if (seg.lattice) {
      sites_[std::size_t(seg.lattice - scene_.lattices.data())].for_each_near(lo, hi, visit);
    } else if (seg.fill) {
      const Vec3d r = largest_radius(seg.fill->spec.size) * Vec3d(1, 1, 1);
      for (std::size_t b : blocks_meeting(seg.fill->blocks, lo - r, hi + r))
        for (const ParticleInit& p : *fill_block(*seg.fill, b))
          if (reaches(p.position, p.radius, lo, hi)) visit(p);
    } else {
      for (std::size_t k = seg.offset; k < seg.offset + seg.count; ++k) {
        const ParticleInit& p = scene_.particles[k];
        if (reaches(p.position, p.radius, lo, hi)) visit(p);
      }
    }
  }
}

std::size_t particle_count(const SceneSpec& scene) {
  std::size_t n = scene.particles.size();
  for (const LatticeSource& l : scene.lattices) n += l.count;
  for (const RandomFillSource& f : scene.fills) n += f.count;
  return n;
}

void for_each_radius(const SceneSpec& scene, const std::function<void(int, double)>& visit) {
  for (const ParticleInit& p : scene.particles) visit(p.material, p.radius);
  for (const LatticeSource& l : scene.lattices)
    if (l.count > 0) visit(l.spec.tmpl.material, l.spec.radius);
  for (const RandomFillSource& f : scene.fills) {
    visit(f.spec.tmpl.material, smallest_radius(f.spec.size));
    visit(f.spec.tmpl.material, largest_radius(f.spec.size));
  }
  // The particles an inlet will insert: its extreme radii bound them all.
  for (const InletSpec& inlet : scene.inlets) {
    visit(inlet.tmpl.material, smallest_radius(inlet.size));
    visit(inlet.tmpl.material, largest_radius(inlet.size));
  }
}

double largest_radius(const SceneSpec& scene) {
  double r = 0;
  for_each_radius(scene, [&](int, double radius) { r = std::max(r, radius); });
  return r;
}

double smallest_radius(const SceneSpec& scene) {
  double r = std::numeric_limits<double>::infinity();
  for_each_radius(scene, [&](int, double radius) { r = std::min(r, radius); });
  return r;
}

namespace {

// Particles handled per task: big enough to amortise a task, small enough
// to spread a lattice over many threads.
constexpr std::size_t kChunk = std::size_t(1) << 16;

// Calls work(chunk, its particles) for the chunks of [first, last) on every
// thread; chunk c holds particles first + c kChunk onwards. An exception (a
// fill too full) is passed on after the loop: that of the first such chunk.
template <class Work>
void in_chunks(const ParticleStream& stream, std::size_t first, std::size_t last, Work&& work) {
  const long chunks = long((last - first + kChunk - 1) / kChunk);
  long failed = chunks;
  std::exception_ptr error;
#pragma omp parallel
  {
    std::vector<ParticleInit> buffer;
#pragma omp for schedule(dynamic)
    for (long c = 0; c < chunks; ++c) {
      try {
        const std::size_t a = first + std::size_t(c) * kChunk;
        buffer.clear();
        stream.generate(a, std::min(last, a + kChunk), buffer);
        work(std::size_t(c), buffer);
      } catch (...) {
#pragma omp critical(gs_in_chunks_error)
        if (c < failed) {
          failed = c;
          error = std::current_exception();
        }
      }
    }
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace

void for_each_particle(const SceneSpec& scene, const std::function<void(const ParticleInit&)>& visit) {
  const ParticleStream stream(scene);
  std::vector<ParticleInit> buffer;
  for (std::size_t a = 0; a < stream.count(); a += kChunk) {
    buffer.clear();
    stream.generate(a, std::min(stream.count(), a + kChunk), buffer);
    for (const ParticleInit& p : buffer) visit(p);
  }
}

std::vector<ParticleInit> all_particles(const SceneSpec& scene) {
  return select_particles(scene, [](const Vec3d&) { return true; });
}

std::vector<ParticleInit> select_particles(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep) {
  std::vector<ParticleInit> out;
  for_each_selected(
      scene, keep, [&out](std::size_t n) { out.resize(n); },
      [&out](std::size_t k, const ParticleInit& p) { out[k] = p; });
  return out;
}

std::vector<ParticleInit> select_particles(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                                           const KeepWindow& window) {
  std::vector<ParticleInit> out;
  for_each_selected_block(
      scene, keep, window, std::numeric_limits<std::size_t>::max(), [&out](std::size_t n) { out.resize(n); },
      [&out](std::size_t k, const ParticleInit& p) { out[k] = p; }, [](std::size_t, std::size_t) {});
  return out;
}

namespace {

void select_blocks(const ParticleStream& stream, const std::function<bool(const Vec3d&)>& keep, std::size_t block,
                   const std::function<void(std::size_t)>& size,
                   const std::function<void(std::size_t, const ParticleInit&)>& write,
                   const std::function<void(std::size_t, std::size_t)>& done) {
  const std::size_t n = stream.count(), chunks = (n + kChunk - 1) / kChunk;
  // offset[c]: the rank of chunk c's first selected particle.
  std::vector<std::size_t> offset(chunks + 1, 0);
  if (keep)
    in_chunks(stream, 0, n, [&](std::size_t c, const std::vector<ParticleInit>& chunk) {
      for (const ParticleInit& p : chunk) offset[c + 1] += keep(p.position) ? 1 : 0;
    });
  else
    for (std::size_t c = 0; c < chunks; ++c) offset[c + 1] = std::min(kChunk, n - c * kChunk);
  for (std::size_t c = 1; c < offset.size(); ++c) offset[c] += offset[c - 1];
  size(offset.back());
  const std::size_t per_block = std::max<std::size_t>(1, block / kChunk);
  for (std::size_t c0 = 0; c0 < chunks; c0 += per_block) {
    const std::size_t c1 = std::min(chunks, c0 + per_block);
    in_chunks(stream, c0 * kChunk, std::min(n, c1 * kChunk),
              [&](std::size_t c, const std::vector<ParticleInit>& chunk) {
                std::size_t k = offset[c0 + c] - offset[c0];
                for (const ParticleInit& p : chunk)
                  if (!keep || keep(p.position)) write(k++, p);
              });
    done(offset[c0], offset[c1] - offset[c0]);
  }
}


}  // namespace

void for_each_selected_block(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                             std::size_t block, const std::function<void(std::size_t)>& size,
                             const std::function<void(std::size_t, const ParticleInit&)>& write,
                             const std::function<void(std::size_t, std::size_t)>& done) {
  select_blocks(ParticleStream(scene), keep, block, size, write, done);
}

// Chunk c's particles may come short of kChunk (blocks outside the window
// are left out), but every one left out is one `keep` refuses: the counts and
// ranks of the selected particles are those of the whole stream.
void for_each_selected_block(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                             const KeepWindow& window, std::size_t block, const std::function<void(std::size_t)>& size,
                             const std::function<void(std::size_t, const ParticleInit&)>& write,
                             const std::function<void(std::size_t, std::size_t)>& done) {
  select_blocks(ParticleStream(scene, window.lo, window.hi), keep, block, size, write, done);
}

void for_each_selected(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                       const std::function<void(std::size_t)>& size,
                       const std::function<void(std::size_t, const ParticleInit&)>& write) {
  // One block: a particle's index within it is its rank.
  for_each_selected_block(scene, keep, std::numeric_limits<std::size_t>::max(), size, write,
      [&](std::size_t, std::size_t) {});
}

void for_each_position_block(const SceneSpec& scene, std::size_t first, std::size_t last,
                             const std::function<void(const std::vector<Vec3d>&)>& use) {
  // Blocks of many chunks, so every thread has work while one block is bounded.
  constexpr std::size_t kBlock = 64 * kChunk;
  const ParticleStream stream(scene);
  last = std::min(last, stream.count());
  std::vector<Vec3d> x;
  for (std::size_t a = first; a < last; a += kBlock) {
    const std::size_t b = std::min(last, a + kBlock);
    x.resize(b - a);
    in_chunks(stream, a, b, [&](std::size_t c, const std::vector<ParticleInit>& chunk) {
      for (std::size_t k = 0; k < chunk.size(); ++k) x[c * kChunk + k] = chunk[k].position;
    });
    use(x);
  }
}

std::size_t find_first(const SceneSpec& scene, std::size_t first, std::size_t last,
                       const std::function<bool(const ParticleInit&)>& bad) {
  const ParticleStream stream(scene);
  last = std::min(last, stream.count());
  std::vector<std::size_t> found((last - first + kChunk - 1) / kChunk, last);
  in_chunks(stream, first, last, [&](std::size_t c, const std::vector<ParticleInit>& chunk) {
    for (std::size_t k = 0; k < chunk.size(); ++k)
      if (bad(chunk[k])) {
        found[c] = first + c * kChunk + k;
        return;
      }
  });
  for (std::size_t f : found)
    if (f < last) return f;
  return last;
}

bool starts_spinning(const SceneSpec& s) {
  auto spins = [](const Vec3d& w) { return norm2(w) > 0; };
  for (const ParticleInit& p : s.particles)
    if (spins(p.angular_velocity)) return true;
  for (const LatticeSource& l : s.lattices)
    if (spins(l.spec.tmpl.angular_velocity)) return true;
  for (const RandomFillSource& f : s.fills)
    if (spins(f.spec.tmpl.angular_velocity)) return true;
  for (const InletSpec& in : s.inlets)
    if (spins(in.tmpl.angular_velocity)) return true;
  return false;
}

}  // namespace gs
