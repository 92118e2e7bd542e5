#pragma once
// A random fill cut into blocks that are filled independently, so that any
// rank or thread makes any block alone, with the same bits, in any order.
//
// The blocks tile the region's bounding box; their number depends on the
// region, the largest diameter and the count only (never on the ranks). A
// block's centres stay a largest radius inside its faces that lie inside the
// region, so spheres of two blocks never overlap and no block needs another.
// Each block gets its share of the count (largest remainder of the volume its
// centres may use), draws its radii from the fill's own counters and places
// them by random sequential addition with a generator keyed by the seed and
// the block's index.
#include <cstddef>
#include <functional>
#include <vector>

#include "scene/generators.hpp"
#include "scene/particle_sets.hpp"

namespace gs {

// Blocks are at least this many largest diameters wide (when the region has
// room): the strip of one largest radius a block keeps clear inside each of
// its inner faces costs up to 6 / (2 kFillBlockDiameters), 7.5 %, of the
// volume its centres may use.
constexpr double kFillBlockDiameters = 40;
// and hold this many particles on average at least, so a dilute fill is not
// cut into many nearly empty blocks.
constexpr std::size_t kFillBlockMinCount = 4096;

// GenerateError when the fill cannot be made at all: a region smaller than
// one particle, a solid fraction beyond random close packing, too many ids.
void check_random_fill(const RandomFillSpec& spec, std::size_t first_id);

// The fill as a source of the scene: its blocks and their counts.
RandomFillSource make_fill_source(const RandomFillSpec& spec, std::size_t first_id);

// Block b's box (a cell of the region's bounds).
void block_box(const FillBlocks& blocks, std::size_t b, Vec3d& lo, Vec3d& hi);
// The block holding the fill's particle `index` (0 .. count - 1).
std::size_t block_of(const FillBlocks& blocks, std::size_t index);
// The blocks whose box meets [lo, hi], ascending.
std::vector<std::size_t> blocks_meeting(const FillBlocks& blocks, const Vec3d& lo, const Vec3d& hi);

// Calls `visit` for every sphere of the earlier sets that reaches into the box [lo, hi].
using SpheresNear = std::function<void(const Vec3d& lo, const Vec3d& hi, const SphereVisitor& visit)>;

// Appends block b's particles (ids first_id + start[b] onwards, largest
// first), clear of the spheres `earlier` visits. GenerateError (naming the
// fill's first particle) when the block is too full.
void generate_fill_block(const RandomFillSource& fill, std::size_t b, const SpheresNear& earlier,
                         std::vector<ParticleInit>& out);

}  // namespace gs
