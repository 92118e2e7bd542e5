#pragma once
// Random-fill blocks made once and kept for the later passes of a rank's
// set-up: the packing checks, the split, and the upload's counting and
// writing passes all read the same blocks, so each is made once per rank.
//
// Kept are the blocks that meet the rank's window (every block offered, until
// a window is set), while their particles fit a byte budget: a block past it
// is handed out but not kept, and is made again where it is needed (with the
// same bits). The memory is that of the rank's own particles and a margin.
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "core/vec3.hpp"
#include "scene/particle_sets.hpp"

namespace gs {

class KeptFillBlocks {
 public:
  using Block = std::shared_ptr<const std::vector<ParticleInit>>;
  explicit KeptFillBlocks(std::size_t budget_bytes) : budget_(budget_bytes) {}

  // Block b of the scene's fill `fill` when kept; null otherwise. Thread-safe.
  Block find(std::size_t fill, std::size_t b) const;
  // A block just made, whose centres lie in [lo, hi]: kept when it meets the
  // window and fits the budget. Thread-safe.
  void offer(std::size_t fill, std::size_t b, const Vec3d& lo, const Vec3d& hi, Block made);
  // From now on only blocks that meet [lo, hi] are kept; kept ones that do
  // not are let go.
  void keep_only(const Vec3d& lo, const Vec3d& hi);

  std::size_t made() const;        // blocks offered so far: how many were made
  std::size_t kept_bytes() const;  // memory of the kept particles

 private:
  struct Kept {
    Vec3d lo, hi;
    Block particles;
  };
  bool meets_window(const Vec3d& lo, const Vec3d& hi) const;

  mutable std::mutex mutex_;
  std::map<std::pair<std::size_t, std::size_t>, Kept> kept_;
  std::size_t budget_, bytes_ = 0, made_ = 0;
  bool windowed_ = false;
  Vec3d window_lo_, window_hi_;
};

// A budget for one rank's kept blocks: a quarter of the host's memory,
// shared among the `ranks_on_host` ranks it runs.
std::size_t kept_blocks_budget(int ranks_on_host);

}  // namespace gs
