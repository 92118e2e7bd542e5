#include "comm/scene_split.hpp"

#include <functional>
#include <utility>

#include "decomposition/metis_decomposition.hpp"
#include "decomposition/slab_decomposition.hpp"
#include "scene/particle_sources.hpp"

namespace gs {
namespace {

// Hands blocks of positions to its argument, one after the other.
using PositionBlocks = std::function<void(const std::function<void(const std::vector<Vec3d>&)>&)>;

void add(Histogram& total, const Histogram& part) {
  for (std::size_t i = 0; i < total.size(); ++i) total[i] += part[i];
}

// The decomposition the positions fed by `blocks` call for: each rank feeds
// its share only, and the counts are summed over the ranks.
std::unique_ptr<Decomposition> decompose(const SceneSpec& scene, Transport& transport, double range,
                                         const PositionBlocks& blocks) {
  const DecompositionSpec& spec = scene.decomposition;
  const int ranks = transport.size();
  if (spec.method == DecompositionMethod::metis) {
    const CoarseGrid grid =
        CoarseGrid::make(scene.domain_min, scene.domain_max, range, MetisDecomposition::kDefaultMaxCells);
    Histogram cells(std::size_t(grid.n_cells()), 0);
    blocks([&](const std::vector<Vec3d>& x) { add(cells, cell_histogram(grid, x)); });
    transport.sum(cells);
    return std::make_unique<MetisDecomposition>(grid, ranks, cells);
  }
  const CoarseGrid grid = CoarseGrid::make(scene.domain_min, scene.domain_max, range);
  if (spec.axis >= 0 && spec.axis <= 2) {
    Histogram layers(std::size_t(grid.dims[std::size_t(spec.axis)]), 0);
    blocks([&](const std::vector<Vec3d>& x) { add(layers, layer_histogram(grid, spec.axis, x)); });
    transport.sum(layers);
    return std::make_unique<SlabDecomposition>(grid, ranks, spec.axis, layers);
  }
  LayerHistograms layers;
  for (std::size_t a = 0; a < 3; ++a) layers[a].assign(std::size_t(grid.dims[a]), 0);
  blocks([&](const std::vector<Vec3d>& x) {
    const LayerHistograms part = layer_histograms(grid, x);
    for (std::size_t a = 0; a < 3; ++a) add(layers[a], part[a]);
  });
  for (Histogram& h : layers) transport.sum(h);
  return std::make_unique<SlabDecomposition>(SlabDecomposition::from_histograms(grid, ranks, spec.axis, layers));
}

std::shared_ptr<DomainExchange> split(const SceneSpec& scene, Transport& transport, const PositionBlocks& blocks) {
  // Ghosts reach one largest diameter, the widest contact, plus the scene's
  // skin (Simulation sets it on the exchange): coarse cells at least that
  // wide keep every rank within a ghost's reach among the decomposition's
  // neighbours.
  const double range = 2 * largest_radius(scene);
  std::unique_ptr<Decomposition> d = decompose(scene, transport, range * (1 + scene.verlet_skin), blocks);
  return std::make_shared<DomainExchange>(transport, std::move(d), range, scene.decomposition, periodic_box(scene));
}

}  // namespace

std::shared_ptr<DomainExchange> split_scene(const SceneSpec& scene, Transport& transport) {
  const std::size_t n = particle_count(scene), k = std::size_t(transport.rank()), ranks = std::size_t(transport.size());
  // n * k overflows only beyond 2^64 / 2^32 ranks: ids are 32-bit.
  const std::size_t first = n * k / ranks, last = n * (k + 1) / ranks;
  const PositionBlocks mine = [&](const std::function<void(const std::vector<Vec3d>&)>& use) {
    for_each_position_block(scene, first, last, use);
  };
  return split(scene, transport, mine);
}

std::shared_ptr<DomainExchange> split_restart(const SceneSpec& scene, Transport& transport,
                                              const std::vector<Vec3d>& share) {
  const PositionBlocks mine = [&](const std::function<void(const std::vector<Vec3d>&)>& use) { use(share); };
  return split(scene, transport, mine);
}

}  // namespace gs
