#pragma once
// A restart with an edited scene (`grainstorm run SCENE --restart CHECKPOINT
// --edited-scene`; docs/OUTPUT.md, "Restarting with an edited scene"): the
// checkpoint's particles, springs and insertion state continue under the
// scene as it is now. What the state cannot follow is refused; what it can,
// is carried over and reported.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/particle_snapshot.hpp"
#include "scene/scene.hpp"
#include "walls/wall.hpp"

namespace gs {

// What the adaptation did on this rank.
struct EditedRestart {
  // Scene walls (by name) that no wall of the checkpoint matches: added, or
  // moved by the edit. The same on every rank.
  std::vector<std::string> new_walls;
  // Checkpoint walls (by index) the scene no longer has. The same on every rank.
  std::vector<std::size_t> gone_walls;
  std::size_t dropped_wall_contacts = 0;  // this rank's contacts with gone walls, released
  int slots_before = 0, slots_after = 0;  // history slots per particle: stored, and the run's
  // History fields the run keeps that the checkpoint lacks (their springs
  // start at zero); HistoryField bits. Seen by the ranks with particles.
  unsigned started_fields = 0;
};

// A stored wall (its pose at the checkpoint's time) is the scene's wall of
// the same kind whose surface lies in the same place at that time (its base
// point, axis or normal, radius and length within 1e-9 of the domain's size);
// each scene wall matches at most one. Contacts with a stored wall follow it
// to its index in the scene; contacts with a wall no longer there are
// released.
//
// Throws std::invalid_argument, naming the particle or the setting, when
//  * a particle's material is not among the scene's materials;
//  * a particle lies outside the domain;
//  * a new or moved wall cuts into a particle by more than 1 % of its radius;
//  * a mesh cuts into a particle by more than 1 % of its radius where the
//    checkpoint holds no contact of that particle with the feature cut (or
//    one next to it): a mesh added, moved or re-meshed by the edit (not
//    checked where the checkpoint holds no contact history);
//  * the scene's inlets are not as many as the checkpoint's (an inlet's
//    state is its count of particles and mass inserted);
//  * a particle has more contacts than the scene's contact_slots.
// The springs are resized to the scene's contact model: fields it does not
// keep are dropped, fields it keeps that the checkpoint lacks start at zero.
// Particles keep their stored radius, mass and inertia.
EditedRestart adapt_to_edited_scene(RestartState& state, const std::vector<Wall>& stored_walls,
                                    const SceneSpec& scene);

// The run log's lines about such a restart: the hashes, the edits value by
// value (scene/scene_edits.hpp; from the checkpoint's scene text, which
// checkpoints written before 2026-12-05 lack), and what the state did about
// them, with `dropped` wall contacts released over all ranks.
std::vector<std::string> edited_restart_lines(const EditedRestart& e, std::size_t dropped, std::uint64_t stored_hash,
                                              std::uint64_t hash, const std::string& stored_text,
                                              const std::string& text, std::size_t scene_walls);

}  // namespace gs
