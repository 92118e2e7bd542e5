#pragma once
// The first decomposition of a run, made without gathering the particles on
// any rank: from the scene's particle sets (a new run) or from a checkpoint's
// positions (a restart), with the interaction range from the sets' radii.
#include <memory>
#include <vector>

#include "comm/domain_exchange.hpp"
#include "comm/transport.hpp"
#include "scene/scene.hpp"

namespace gs {

// A new run: each rank generates the positions of its share of the particles
// (an even split of the id sequence) into the coarse histograms, which are
// summed over the ranks. Counts are integers, so the sum, and the
// decomposition, are those of all positions on one rank. Collective.
std::shared_ptr<DomainExchange> split_scene(const SceneSpec& scene, Transport& transport);

// A restart: each rank holds its share of the checkpoint's positions (any
// split of them over the ranks); the counts are summed as for a new run.
// Collective.
std::shared_ptr<DomainExchange> split_restart(const SceneSpec& scene, Transport& transport,
                                              const std::vector<Vec3d>& share);

}  // namespace gs
