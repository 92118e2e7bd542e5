#include "scene/particle_sources.hpp"

#include <algorithm>
#include <limits>

#include "scene/generators.hpp"

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

ParticleStream::ParticleStream(const SceneSpec& scene) : scene_(scene) {
  const std::vector<ParticleInit>& listed = scene.particles;
  std::size_t e = 0;
  auto add = [&](const LatticeSource* lattice, std::size_t offset, std::size_t count) {
    if (count == 0) return;
    segments_.push_back({lattice, offset, count_, count});
    count_ += count;
  };
  for (const LatticeSource& l : scene.lattices) {
    const std::size_t run = e;
    while (e < listed.size() && listed[e].id < l.first_id) ++e;
    add(nullptr, run, e - run);
    sites_.emplace_back(l.spec, l.first_id);
    add(&l, 0, l.count);
  }
  add(nullptr, e, listed.size() - e);
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
    } else {
      const auto begin = scene_.particles.begin() + std::ptrdiff_t(seg->offset);
      out.insert(out.end(), begin + std::ptrdiff_t(from), begin + std::ptrdiff_t(to));
    }
    first = seg->begin + to;
  }
}

std::size_t particle_count(const SceneSpec& scene) {
  std::size_t n = scene.particles.size();
  for (const LatticeSource& l : scene.lattices) n += l.count;
  return n;
}

void for_each_radius(const SceneSpec& scene, const std::function<void(int, double)>& visit) {
  for (const ParticleInit& p : scene.particles) visit(p.material, p.radius);
  for (const LatticeSource& l : scene.lattices)
    if (l.count > 0) visit(l.spec.tmpl.material, l.spec.radius);
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
// thread; chunk c holds particles first + c kChunk onwards.
template <class Work>
void in_chunks(const ParticleStream& stream, std::size_t first, std::size_t last, Work&& work) {
  const long chunks = long((last - first + kChunk - 1) / kChunk);
#pragma omp parallel
  {
    std::vector<ParticleInit> buffer;
#pragma omp for schedule(dynamic)
    for (long c = 0; c < chunks; ++c) {
      const std::size_t a = first + std::size_t(c) * kChunk;
      buffer.clear();
      stream.generate(a, std::min(last, a + kChunk), buffer);
      work(std::size_t(c), buffer);
    }
  }
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

void for_each_selected_block(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                             std::size_t block, const std::function<void(std::size_t)>& size,
                             const std::function<void(std::size_t, const ParticleInit&)>& write,
                             const std::function<void(std::size_t, std::size_t)>& done) {
  const ParticleStream stream(scene);
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

}  // namespace gs
