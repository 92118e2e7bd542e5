#include "scene/kept_fill_blocks.hpp"

#include <algorithm>
#include <unistd.h>

namespace gs {

bool KeptFillBlocks::meets_window(const Vec3d& lo, const Vec3d& hi) const {
  if (!windowed_) return true;
  return lo.x <= window_hi_.x && lo.y <= window_hi_.y && lo.z <= window_hi_.z && hi.x >= window_lo_.x &&
         hi.y >= window_lo_.y && hi.z >= window_lo_.z;
}

KeptFillBlocks::Block KeptFillBlocks::find(std::size_t fill, std::size_t b) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = kept_.find({fill, b});
  return it == kept_.end() ? nullptr : it->second.particles;
}

void KeptFillBlocks::offer(std::size_t fill, std::size_t b, const Vec3d& lo, const Vec3d& hi, Block made) {
  const std::size_t bytes = made->size() * sizeof(ParticleInit);
  const std::lock_guard<std::mutex> lock(mutex_);
  ++made_;
  if (!meets_window(lo, hi) || bytes_ + bytes > budget_) return;
  // Two threads may make the same block at once (the same bits): one is kept.
  if (kept_.emplace(std::make_pair(fill, b), Kept{lo, hi, std::move(made)}).second) bytes_ += bytes;
}

void KeptFillBlocks::keep_only(const Vec3d& lo, const Vec3d& hi) {
  const std::lock_guard<std::mutex> lock(mutex_);
  windowed_ = true;
  window_lo_ = lo;
  window_hi_ = hi;
  for (auto it = kept_.begin(); it != kept_.end();) {
    if (meets_window(it->second.lo, it->second.hi)) {
      ++it;
      continue;
    }
    bytes_ -= it->second.particles->size() * sizeof(ParticleInit);
    it = kept_.erase(it);
  }
}

std::size_t KeptFillBlocks::made() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return made_;
}

std::size_t KeptFillBlocks::kept_bytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

std::size_t kept_blocks_budget(int ranks_on_host) {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  // Unknown memory: 4 GiB, enough to keep a few times 1e7 particles.
  const double host = pages > 0 && page > 0 ? double(pages) * double(page) : 16.0 * (1ull << 30);
  return std::size_t(host / 4 / std::max(1, ranks_on_host));
}

}  // namespace gs
