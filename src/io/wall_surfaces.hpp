#pragma once
// The analytic walls as triangles at their current pose, so a viewer shows
// them beside the particles (docs/OUTPUT.md): a plane is the polygon it cuts
// out of the domain box, a disk a fan, a cylinder and a cone a band of quads,
// a plate a ring from its hole's rim to its outer circle.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/h5_io.hpp"
#include "walls/wall.hpp"

namespace gs {

// Segments around a disk's rim and a cylinder's circumference.
constexpr int kWallSurfaceSegments = 64;

struct WallSurface {
  std::vector<Vec3d> vertices;                       // world frame [m]
  std::vector<std::array<std::int32_t, 3>> triangles;  // vertex indices
};

// The axis-aligned box a plane is clipped to (the scene's domain).
struct DomainBox {
  Vec3d min, max;
};

// Wall w at its current pose. A plane that misses the box is drawn as a
// square in the plane, centred at the foot of the box centre, as wide as the
// box's diagonal.
WallSurface wall_surface(const Wall& w, const DomainBox& box);

// Group `group` (created here) with one subgroup per wall, named by its index:
// `vertices` (V, 3) float64 and `triangles` (T, 3) int32, and a string
// attribute `name` (names[k], or "wall_<k>" when the walls are unnamed), an
// int32 attribute `active` (0 while the wall is outside its active window; it
// is drawn all the same).
void write_wall_surfaces(const h5::File& f, const std::string& group, const std::vector<Wall>& walls,
                         const std::vector<std::string>& names, const DomainBox& box);

// What an index needs of each wall surface in a file: its name and sizes.
struct WallSurfaceInfo {
  std::string name;
  std::size_t vertices = 0, triangles = 0;
};
// Read back from `group`; empty when the file has no such group.
std::vector<WallSurfaceInfo> read_wall_surface_info(const h5::File& f, const std::string& group);

}  // namespace gs
