#pragma once
// A box around what a rank owns, for work that can skip the rest of space
// (setup generates only the random-fill blocks that meet it).
#include "decomposition/decomposition.hpp"

namespace gs {

// The bounding box of `rank`'s coarse cells; a side on the domain's boundary
// extends to infinity, as ownership does there. lo > hi on some axis when the
// rank owns no cell.
void owned_bounds(const Decomposition& decomposition, int rank, Vec3d& lo, Vec3d& hi);

}  // namespace gs
