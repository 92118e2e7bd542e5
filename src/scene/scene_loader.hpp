#pragma once
#include <string>

#include "scene/scene.hpp"

namespace gs {

// Who checks the initial packing (scene/packing_check.hpp), which makes every
// particle: the loader (`here`), or the caller, as a run's ranks do, each over
// the particles it makes anyway (`by_caller`).
enum class PackingChecks { here, by_caller };

// Reads and validates a scene file (format: docs/SCENES.md), describes its
// particles and resolves the time step. Throws SceneError with a message
// "<file>:<line>: <key path>: <what is wrong>".
SceneSpec load_scene(const std::string& path, PackingChecks checks = PackingChecks::here);

// The same for scene text held in memory; `source_name` stands for the file
// name in messages and in SceneSpec::path.
SceneSpec parse_scene(const std::string& yaml_text, const std::string& source_name,
                      PackingChecks checks = PackingChecks::here);

// Depth [m] by which a sphere (centre c, radius r) cuts into a wall in its
// reference pose; <= 0 when it is clear. Planes count the whole back side as
// inside the wall; a cylinder only counts where c projects onto [0, length].
double wall_penetration(const Wall& wall, const Vec3d& c, double r);

}  // namespace gs
