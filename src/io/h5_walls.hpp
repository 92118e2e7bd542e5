#pragma once
// Analytic walls in an HDF5 group (docs/OUTPUT.md): reference geometry,
// prescribed motion, current pose, and the current point and normal, enough
// to draw each wall and to restore it exactly on restart.
#include <array>
#include <string>
#include <vector>

#include "io/h5_io.hpp"
#include "walls/wall.hpp"

namespace gs {

// Writes group `group` (created here) with one row per wall; `names` is empty
// or holds one name per wall.
void write_walls(const h5::File& f, const std::string& group, const std::vector<Wall>& walls,
                 const std::vector<std::string>& names);
// Walls as write_walls stored them, bit for bit; FormatError on a bad group.
std::vector<Wall> read_walls(const h5::File& f, const std::string& group);

// One wall as plain numbers, for checksums: kind, material, point, normal,
// radius, length, velocity, angular_velocity, axis_point, rotation, shift.
constexpr int kWallStateSize = 31;
std::array<double, kWallStateSize> wall_state(const Wall& w);

}  // namespace gs
