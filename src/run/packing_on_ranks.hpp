#pragma once
// The packing checks of a new run (scene/packing_check.hpp) spread over its
// ranks: each rank checks the particles it makes anyway, and the ranks agree
// on the first offence in id order, which every rank reports alike (the set's
// file:line and key), so every rank stops with the same message. The scene is
// loaded with PackingChecks::by_caller; no rank makes every particle.
#include "comm/transport.hpp"
#include "engine/rank_exchange.hpp"
#include "scene/scene.hpp"

namespace gs {

// Before the split. Rank k of K checks that ids [k N / K, (k+1) N / K) fit
// the domain and the walls: the share whose positions the split reads next,
// from the same random-fill blocks (kept in scene.kept_blocks). Collective;
// RankFailure on every rank when any particle does not fit or a fill's block
// cannot be made.
void check_fit_on_ranks(const SceneSpec& scene, Transport& transport);

// After it (`split` null on one rank). Each rank checks the particles it owns
// against those of lower ids within a largest diameter of its region: the
// overlaps between sets. Collective; RankFailure on every rank at the first
// overlapping particle. Then the scene's kept blocks are cut to those the
// rank's upload reads (the blocks meeting its region).
void check_overlaps_on_ranks(const SceneSpec& scene, Transport& transport, const RankExchange* split);

}  // namespace gs
