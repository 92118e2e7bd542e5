#pragma once
// Section parsers of the scene loader that live outside scene_loader.cpp.
#include "scene/fill_region.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/scene_loader.hpp"
#include "walls/triangle_mesh.hpp"

namespace gs::scene_yaml {

// Index of the material named by v; error naming the known ones otherwise.
int material_index(const SceneSpec& s, const Val& v);

// `walls:` -> s.walls and s.wall_names (needs s.materials).
void parse_walls(const Map& top, SceneSpec& s);
// The triangles of the STL file an entry names under `stl` (relative to the
// scene file), read with its `scale` and `weld_tolerance`; a file that
// cannot be read fails naming the entry's `stl` (scene_walls.cpp).
TriangleMesh read_scene_stl(const Map& m, const SceneSpec& s);

// Refuses a mesh whose binning in cells of `cell_size` for the Verlet skin
// `skin` (run_binning) would exceed the limits of bin_triangles
// (walls/mesh.hpp), naming the mesh and its size against the domain (needs
// s.meshes and the walls section).
void check_mesh_binning(const Map& top, const SceneSpec& s, double cell_size, double skin);

// `domain.periodic` (a list of axes) -> a set of axis bits; scene_periodic.cpp.
unsigned parse_periodic_axes(const Val& v);
// Refuses a face listed in `domain.open` whose axis is periodic (needs
// s.open_faces and s.periodic_axes): a particle leaving through it wraps.
void check_open_periodic_faces(const Map& domain, const SceneSpec& s);
// Refuses a wall of walls[first_wall, end), all from the entry `item`, that
// cannot meet the periodic faces (needs s.periodic_axes and the domain).
void check_periodic_walls(const SceneSpec& s, std::size_t first_wall, const Val& item);
// Refuses a periodic box shorter than two largest diameters along a periodic
// axis, and meshes that come near its periodic faces (needs the particles).
void check_periodic_box(const Map& top, const SceneSpec& s);
// Parts of a particle set shared by `particles:` and `inlets:`
// (scene_particles.cpp): material, velocities and marker; a region (box or
// cylinder); the sizes (radius, a range, or a distribution by count or mass).
ParticleTemplate parse_template(const SceneSpec& s, const Map& m);
FillRegion parse_region(const Val& v);
SizeSpec parse_sizes(const Map& m);

// `inlets:` -> s.inlets, checked against the domain and the sizes (needs
// s.materials); check_inlet_rates then refuses a rate no batch can place
// (needs the time step). scene_inlets.cpp.
void parse_inlets(const Map& top, SceneSpec& s);
void check_inlet_rates(const Map& top, SceneSpec& s);

// `particles:` -> s.particles, then checks them against the domain, the walls
// and each other (needs s.materials, s.walls and the domain).
void parse_particles(const Map& top, SceneSpec& s, PackingChecks checks);

// `analysis:` -> s.mixing (needs the domain and the duration); scene_analysis.cpp.
void parse_analysis(const Map& top, SceneSpec& s);

// `marking:` -> s.marking (needs the duration); scene_marking.cpp.
void parse_marking(const Map& top, SceneSpec& s);

// `domain.open` -> s.open_faces; `outlets:` -> s.outlets (needs the domain);
// scene_outlets.cpp.
void parse_open_faces(const Map& domain, SceneSpec& s);
void parse_outlets(const Map& top, SceneSpec& s);
// `measurements:` -> s.measurements (needs the domain, the duration and the time step); scene_measurements.cpp.
void parse_measurements(const Map& top, SceneSpec& s);

}  // namespace gs::scene_yaml
