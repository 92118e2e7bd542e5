#pragma once
#include <vector>

#include "coarse_grid.hpp"

namespace gs {

// Partitions the coarse cells of grid into n_parts with METIS and returns the
// part of every cell (indexed by CoarseGrid::index).
//
// Graph: one vertex per cell, edges between face-adjacent cells. Vertex
// weight 1 + particles + extra load, so empty cells still cost something (a
// rank pays for scanning them). Edge weight 1 + the mean weight of its two
// cells, so METIS prefers to cut through sparse regions where the halo holds
// few ghosts. Weights are divided by a common integer factor when needed so
// that METIS's 32-bit sums cannot overflow. The seed is fixed and METIS is
// serial, so the result is a deterministic function of the inputs.
// cell_load: empty, or one extra weight per cell (e.g. contacts).
// Throws std::runtime_error naming the METIS call and its code on failure.
std::vector<int> metis_partition(const CoarseGrid& grid, int n_parts, const Histogram& cell_counts,
                                 const Histogram& cell_load, int seed);

}  // namespace gs
