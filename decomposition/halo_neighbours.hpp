#pragma once
// Which ranks trade ghosts, found from the ownership table itself, so that a
// halo reaching across a periodic face finds the rank on the other side (the
// last slab along a periodic axis neighbours the first; METIS parts likewise).
#include <vector>

#include "core/owner_map.hpp"

namespace gs {

// For each rank r, ascending and without r: every rank owning a cell within
// box distance `halo` of one of r's cells, the distance taken across the
// periodic faces of map.shape.box. Symmetric (a in [b] iff b in [a]), and
// computed alike on every rank from the same table. Cost: one halo query per
// coarse cell (per layer for slabs).
std::vector<std::vector<int>> halo_neighbours(const OwnerMapHost& map, double halo, int ranks);

}  // namespace gs
