#include "run/packing_on_ranks.hpp"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <functional>
#include <vector>

#include "comm/rank_agreement.hpp"
#include "scene/generators.hpp"
#include "scene/kept_fill_blocks.hpp"
#include "scene/packing_check.hpp"
#include "scene/particle_sources.hpp"

namespace gs {
namespace {

// The lowest of every rank's `value`. Collective.
std::size_t lowest(Transport& transport, std::size_t value) {
  std::vector<std::int64_t> each(std::size_t(transport.size()), 0);
  each[std::size_t(transport.rank())] = std::int64_t(value);
  transport.sum(each);
  return std::size_t(*std::min_element(each.begin(), each.end()));
}

// Runs `find` (the first offence among this rank's particles, or n); then
// every rank learns the first over all ranks and reports it with `report`:
// the same message on every rank. A block that cannot be made is reported
// where its set was defined. Collective.
void agree(const SceneSpec& scene, Transport& transport, const std::function<std::size_t()>& find,
           void (*report)(const SceneSpec&, std::size_t)) {
  const std::size_t n = particle_count(scene);
  std::size_t mine = n;
  std::string error;
  auto as_message = [&](auto&& f) {
    try {
      f();
    } catch (const GenerateError& e) {
      try {
        report_generate_error(scene, e);
      } catch (const std::exception& located) {
        error = located.what();
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
  };
  as_message([&] { mine = find(); });
  throw_if_any_failed(transport, error);
  const std::size_t first = lowest(transport, mine);
  if (first < n) as_message([&] { report(scene, first); });
  throw_if_any_failed(transport, error);
}

}  // namespace

void check_fit_on_ranks(const SceneSpec& scene, Transport& transport) {
  const std::size_t n = particle_count(scene), k = std::size_t(transport.rank()),
                    ranks = std::size_t(transport.size());
  const std::size_t first = n * k / ranks, last = n * (k + 1) / ranks;
  agree(scene, transport, [&] {
    const std::size_t bad = first_misfit(scene, first, last);
    return bad < last ? bad : n;
  }, report_misfit);
}

void check_overlaps_on_ranks(const SceneSpec& scene, Transport& transport, const RankExchange* split) {
  ParticleShare share = every_particle();
  if (split) {
    share.keep = [split](const Vec3d& x) { return split->owns(x); };
    split->owned_bounds(share.window.lo, share.window.hi);
  }
  KeptFillBlocks* kept = scene.kept_blocks.get();
  const bool windowed = kept && split;
  if (sets_may_overlap(scene)) {  // the same answer on every rank: all or none of them meet here
    // The blocks within reach of the region are kept while the check reads them twice.
    const double r = 2 * largest_radius(scene);
    if (windowed) kept->keep_only(share.window.lo - Vec3d(r, r, r), share.window.hi + Vec3d(r, r, r));
    agree(scene, transport, [&] { return first_overlapping(scene, share); }, report_overlap);
  }
  if (windowed) kept->keep_only(share.window.lo, share.window.hi);  // what the upload reads
}

}  // namespace gs
