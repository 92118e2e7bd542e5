#pragma once
// The scene's particles generated where they are needed, never all at once:
// any range of them in id order, on every thread, and the few numbers the
// setup needs from all of them (count, radii) without generating any.
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "scene/scene.hpp"

namespace gs {

// The particle of any site of a lattice, on its own: sites are independent,
// so any range of them can be made by any thread or rank, in any order, with
// the same bits as the serial generator.
class LatticeSites {
 public:
  LatticeSites(const LatticeSpec& spec, ParticleId first_id);
  std::size_t count() const { return nx_ * ny_ * nz_; }
  ParticleInit at(std::size_t site) const;
  // Calls visit for the sites whose sphere reaches into the box [lo, hi].
  void for_each_near(const Vec3d& lo, const Vec3d& hi, const std::function<void(const ParticleInit&)>& visit) const;

 private:
  LatticeSpec spec_;
  ParticleId first_id_;
  std::size_t nx_, ny_, nz_;
};

// The scene's particles as one sequence in id order: the explicit particles
// (SceneSpec::particles, ascending ids) merged with the lattices and random
// fills by id. A fill's blocks are made on demand (scene/fill_blocks.hpp),
// the last few kept for the next caller (any thread), and those the scene's
// KeptFillBlocks keeps (when it has one) for every later stream.
class ParticleStream {
 public:
  explicit ParticleStream(const SceneSpec& scene);
  // With a window: random-fill blocks that do not meet the box [lo, hi] are
  // left out (generate skips their particles), for callers that keep only
  // particles inside the window anyway.
  ParticleStream(const SceneSpec& scene, const Vec3d& lo, const Vec3d& hi);
  std::size_t count() const { return count_; }
  // Appends particles [first, last) of the sequence to out (less those of
  // blocks outside the window). Thread-safe.
  void generate(std::size_t first, std::size_t last, std::vector<ParticleInit>& out) const;
  // Calls visit for the particles before `before` whose sphere reaches into
  // the box [lo, hi]: the obstacles a fill's block must avoid.
  void for_each_near(std::size_t before, const Vec3d& lo, const Vec3d& hi,
                     const std::function<void(const ParticleInit&)>& visit) const;

 private:
  // A run of explicit particles (no source: particles[offset ...]), a whole lattice or a whole fill.
  struct Segment {
    const LatticeSource* lattice;
    const RandomFillSource* fill;
    std::size_t offset, begin, count;  // begin: index of its first particle in the sequence
  };
  using Block = std::shared_ptr<const std::vector<ParticleInit>>;
  struct CachedBlock {
    const RandomFillSource* fill;
    std::size_t block;
    Block particles;
  };
  Block fill_block(const RandomFillSource& fill, std::size_t b) const;
  bool in_window(const RandomFillSource& fill, std::size_t b) const;

  const SceneSpec& scene_;
  std::vector<Segment> segments_;
  std::vector<LatticeSites> sites_;  // one per lattice
  std::size_t count_ = 0;
  bool windowed_ = false;
  Vec3d window_lo_, window_hi_;
  mutable std::mutex cache_mutex_;
  mutable std::vector<CachedBlock> cache_;  // a ring of recent blocks
  mutable std::size_t cache_next_ = 0;
};

std::size_t particle_count(const SceneSpec& scene);
// Calls visit(material, radius) for every explicit particle, once per
// lattice, and for the smallest and largest radius of each random fill and
// inlet: bounds of every radius the run can have, without generating a set.
void for_each_radius(const SceneSpec& scene, const std::function<void(int material, double radius)>& visit);
double largest_radius(const SceneSpec& scene);   // 0 without particles
double smallest_radius(const SceneSpec& scene);  // infinity without particles

// Every particle in id order, one after the other (serial; for checks that
// need the order, and small scenes).
void for_each_particle(const SceneSpec& scene, const std::function<void(const ParticleInit&)>& visit);
std::vector<ParticleInit> all_particles(const SceneSpec& scene);

// The particles whose position `keep` accepts, in id order, generated in
// chunks on every thread (keep must be safe to call from several threads).
std::vector<ParticleInit> select_particles(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep);

// The same without a list of them: the particles `keep` accepts (all of them
// when `keep` is empty, which needs no counting pass) are counted chunk by
// chunk (one pass, every thread), `size(n)` is told how many there are, then
// each is handed to `write(k, particle)` with its rank k in id order (a
// second pass; several threads at once, each k once). Setup fills its arrays
// this way, so no copy of the particles is ever held.
void for_each_selected(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                       const std::function<void(std::size_t)>& size,
                       const std::function<void(std::size_t, const ParticleInit&)>& write);

// The same in blocks of about `block` selected particles, in id order: `write`
// gets each particle's index within its block, and `done(first, count)` (on
// the calling thread) follows each block with the rank of its first particle
// and its length. Setup uploads each block while the host holds only one.
void for_each_selected_block(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                             std::size_t block, const std::function<void(std::size_t)>& size,
                             const std::function<void(std::size_t, const ParticleInit&)>& write,
                             const std::function<void(std::size_t first, std::size_t count)>& done);

// Where `keep` can accept anything: a box that holds every position it
// accepts. Random-fill blocks outside it are never made.
struct KeepWindow {
  Vec3d lo, hi;
};
void for_each_selected_block(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                             const KeepWindow& window, std::size_t block, const std::function<void(std::size_t)>& size,
                             const std::function<void(std::size_t, const ParticleInit&)>& write,
                             const std::function<void(std::size_t first, std::size_t count)>& done);

// The particles `keep` accepts within the window (random-fill blocks outside
// it are never made), in id order.
std::vector<ParticleInit> select_particles(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                                           const KeepWindow& window);

// Positions of particles [first, last) of the sequence, in blocks generated
// on every thread and handed to `use` one after the other, in order.
void for_each_position_block(const SceneSpec& scene, std::size_t first, std::size_t last,
                             const std::function<void(const std::vector<Vec3d>&)>& use);

// Index in the sequence of the first particle of [first, last) that `bad`
// accepts, or `last`; searched on every thread.
std::size_t find_first(const SceneSpec& scene, std::size_t first, std::size_t last,
                       const std::function<bool(const ParticleInit&)>& bad);

}  // namespace gs
