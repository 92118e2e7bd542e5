#pragma once
// The checks of a scene's initial packing: every particle fits the domain and
// clears the walls present at t = 0, and particles of different sets do not
// overlap. The loader runs them over every particle; a run on several ranks
// runs them instead on each rank over the particles that rank makes anyway
// (src/run/packing_on_ranks.hpp), and the first offence in id order over all
// ranks is the verdict, reported alike on every rank.
#include <cstddef>
#include <functional>
#include <string>

#include "scene/particle_sources.hpp"
#include "scene/scene.hpp"

namespace gs {

// Rounding in generated positions must not turn "touching" into "overlapping".
constexpr double kTouchTolerance = 1e-9;

// Id of the first particle of ids [first, last) that does not fit the domain
// or the walls; `last` when all of them fit. GenerateError when a random
// fill's block among them cannot be made.
std::size_t first_misfit(const SceneSpec& scene, std::size_t first, std::size_t last);

// Whether particles of the scene can overlap at all: more than one set, or a
// list (a lattice or a random fill alone never overlaps itself).
bool sets_may_overlap(const SceneSpec& scene);

// The particles one rank answers for: those whose position `keep` accepts
// (every one when `keep` is empty), all inside the box [lo, hi].
struct ParticleShare {
  std::function<bool(const Vec3d&)> keep;
  KeepWindow window;
};
ParticleShare every_particle();

// Id of the first particle of the share that overlaps a particle of a lower
// id (any rank's); particle_count(scene) when none does. Makes the particles
// within a largest diameter of the share's box.
std::size_t first_overlapping(const SceneSpec& scene, const ParticleShare& share);

// SceneError at particle `id`'s set (its file:line and key): why it does not
// fit; why it overlaps the particle of lowest id it overlaps.
[[noreturn]] void report_misfit(const SceneSpec& scene, std::size_t id);
[[noreturn]] void report_overlap(const SceneSpec& scene, std::size_t id);
// SceneError at the set that failed to generate (GenerateError::set_first),
// or at the first set when that is not known.
[[noreturn]] void report_generate_error(const SceneSpec& scene, const std::exception& error);

// Both checks over every particle, on this process alone: SceneError on the
// first offence.
void check_packing(const SceneSpec& scene);

}  // namespace gs
