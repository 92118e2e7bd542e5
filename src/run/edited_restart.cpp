#include "run/edited_restart.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contact/contact_models.hpp"
#include "core/types.hpp"
#include "io/fnv1a.hpp"
#include "scene/scene_edits.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_yaml.hpp"
#include "walls/mesh.hpp"
#include "walls/sphere_triangle.hpp"
#include "walls/timeline.hpp"
#include "walls/wall_geometry.hpp"
#include "walls/wall_motion.hpp"

namespace gs {
namespace {

using scene_yaml::str;

// An added wall may touch the particles (a settled bed presses on whatever
// holds it), but not cut into them deeper than this share of a radius.
constexpr double kNewWallCut = 0.01;

std::string particle_at(const RestartState& s, std::size_t i) {
  return "particle " + std::to_string(s.particles.id[i]) + " at " + str(s.particles.position[i]);
}

// Whether two posed walls have the same surface: the same kind, world normal
// or axis, radius and length, and base point (of a plane, any point of it).
bool same_surface(const Wall& a, const Wall& b, double tolerance) {
  if (a.kind != b.kind) return false;
  const Vec3d pa = wall_to_world(a, a.point), pb = wall_to_world(b, b.point);
  const Vec3d na = wall_rotate(a, a.normal), nb = wall_rotate(b, b.normal);
  const double apart = a.kind == WallKind::plane ? std::abs(dot(pa - pb, na)) : norm(pa - pb);
  return apart <= tolerance && norm(na - nb) <= 1e-9 && std::abs(a.radius - b.radius) <= tolerance &&
         std::abs(a.length - b.length) <= tolerance;
}

// For each stored wall, its index among the scene's walls posed at `time`, or -1.
std::vector<int> match_walls(const std::vector<Wall>& stored, const SceneSpec& scene, double time,
                             std::vector<Wall>& posed) {
  const double tolerance = 1e-9 * norm(scene.domain_max - scene.domain_min);
  posed.clear();
  for (std::size_t k = 0; k < scene.walls.size(); ++k)
    posed.push_back(wall_at(scene.walls[k], timeline_of(scene.wall_timelines, k), time));
  std::vector<int> to(stored.size(), -1);
  std::vector<bool> taken(posed.size(), false);
  for (std::size_t w = 0; w < stored.size(); ++w)
    for (std::size_t k = 0; k < posed.size(); ++k)
      if (!taken[k] && same_surface(stored[w], posed[k], tolerance)) {
        to[w] = int(k);
        taken[k] = true;
        break;
      }
  return to;
}

void check_particles(const RestartState& s, const SceneSpec& scene) {
  const ParticleRecords& p = s.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] >= scene.materials.size())
      throw std::invalid_argument(particle_at(s, i) + " is of material " + std::to_string(int(p.material[i])) +
                                  ", but the edited scene has " + std::to_string(scene.materials.size()) +
                                  " materials (remove none that particles of the checkpoint are made of)");
    const Vec3d& x = p.position[i];
    const Vec3d &lo = scene.domain_min, &hi = scene.domain_max;
    if (x.x < lo.x || x.y < lo.y || x.z < lo.z || x.x > hi.x || x.y > hi.y || x.z > hi.z)
      throw std::invalid_argument(particle_at(s, i) + " is not inside the edited scene's domain " + str(lo) +
                                  " .. " + str(hi));
  }
}

void check_new_walls(const RestartState& s, const SceneSpec& scene, const std::vector<Wall>& posed,
                     const std::vector<bool>& matched) {
  const ParticleRecords& p = s.particles;
  for (std::size_t k = 0; k < posed.size(); ++k) {
    if (matched[k] || !posed[k].active) continue;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double r = p.radius[i];
      const double depth = wall_penetration(scene.walls[k], wall_to_reference(posed[k], p.position[i]), r);
      if (depth > kNewWallCut * r)
        throw std::invalid_argument("wall " + scene_yaml::quoted(scene.wall_names[k]) +
                                    ", which the checkpoint does not have (added, or moved by the edit), cuts " +
                                    str(depth) + " m into " + particle_at(s, i) + " with radius " + str(r) +
                                    " (more than " + str(100 * kNewWallCut) + " % of it)");
    }
  }
}

// Whether particle i's stored contacts name the mesh feature `key` or one
// next to it (the contact the force kernel would carry on).
bool stored_mesh_contact(const HostHistory& h, std::size_t i, const MeshView& m, std::uint32_t key) {
  const SameMeshContact same{&m, key};
  for (std::size_t k = 0; k < std::size_t(h.slots); ++k)
    if (same(h.partner[i * std::size_t(h.slots) + k])) return true;
  return false;
}

// A mesh that cuts into a particle where the checkpoint holds no contact of
// that particle with the feature (or one next to it) was added, moved or
// re-meshed by the edit. Without contact history (a frictionless law that
// keeps none) there is nothing to tell a new cut from an old contact by, and
// nothing is checked.
void check_meshes(const RestartState& s, const SceneSpec& scene) {
  const ParticleRecords& p = s.particles;
  const HostHistory& h = p.history;
  if (scene.meshes.n_triangles() == 0 || p.size() == 0 || h.slots == 0) return;
  MeshSet posed = scene.meshes;
  move_meshes(posed, s.time);
  // Cells twice as wide as the run's narrowest (a diameter and the skin): no
  // more of them than the run bins its meshes in, whose binning would refuse first.
  const double cell = 4 * double(*std::max_element(p.radius.begin(), p.radius.end())) * (1 + scene.verlet_skin);
  const MeshBins bins = bin_triangles(posed, cell, run_binning(cell, 0));
  const MeshView view = with_bins(posed.view(), bins);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    auto cut = [&](const MeshContact& c) {
      if (c.overlap <= kNewWallCut * r || stored_mesh_contact(h, i, view, c.feature_key)) return;
      throw std::invalid_argument("mesh " + scene_yaml::quoted(posed.names[std::size_t(c.mesh)]) + " cuts " +
                                  str(c.overlap) + " m into " + particle_at(s, i) + " with radius " + str(r) +
                                  " (more than " + str(100 * kNewWallCut) +
                                  " % of it) where the checkpoint holds no contact with it (added, moved or "
                                  "re-meshed by the edit)");
    };
    for_each_mesh_contact(view, p.position[i], r, cut);
  }
}

void check_inlets(const RestartState& s, const SceneSpec& scene) {
  const std::size_t stored = s.insertion ? s.insertion->inlets.size() : 0;
  if (stored != scene.inlets.size())
    throw std::invalid_argument("the checkpoint holds the state of " + std::to_string(stored) +
                                " inlets, the edited scene has " + std::to_string(scene.inlets.size()) +
                                ": inlets can be edited but not added or removed on a restart");
}

bool is_wall_partner(ParticleId p) { return p >= kWallPartnerBase && p != kNoPartner; }

// The stored rows re-laid to `width` contacts per particle with the fields
// `kept`: a contact keeps its slot where the row is at least as wide as before,
// otherwise the row's contacts are packed to its front in their order;
// contacts with walls follow `wall_to` or are released.
HostHistory relaid(const RestartState& s, const std::vector<int>& wall_to, int width, unsigned kept,
                   EditedRestart& report) {
  const HostHistory& h = s.particles.history;
  const std::size_t n = s.particles.size(), from = std::size_t(h.slots), to = std::size_t(width);
  HostHistory out;
  out.slots = width;
  if (to == 0) return out;  // a model without springs: every contact's history is dropped
  out.partner.assign(n * to, kNoPartner);
  for_each_history_field(out, h, [&](const char*, unsigned bit, auto& field, const auto& stored) {
    if (!(kept & bit)) return;
    field.assign(n * to, {});
    if (stored.empty() && (n > 0 || from == 0)) report.started_fields |= bit;
  });
  std::vector<ParticleId> partners(from);  // a row's, as the scene numbers them; kNoPartner: none
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t contacts = 0;
    for (std::size_t k = 0; k < from; ++k) {
      ParticleId& partner = partners[k] = h.partner[i * from + k];
      if (partner == kNoPartner) continue;
      if (is_wall_partner(partner)) {
        const std::size_t w = partner - kWallPartnerBase;
        const bool gone = w >= wall_to.size() || wall_to[w] < 0;
        report.dropped_wall_contacts += gone;
        partner = gone ? kNoPartner : kWallPartnerBase + ParticleId(wall_to[w]);
      }
      contacts += partner != kNoPartner;
    }
    if (contacts > to)
      throw std::invalid_argument("particle " + std::to_string(s.particles.id[i]) + " has " +
                                  std::to_string(contacts) + " contacts, more than the edited scene's contact_slots (" +
                                  std::to_string(width) + ")");
    std::size_t next = 0;
    for (std::size_t k = 0; k < from; ++k) {
      const ParticleId partner = partners[k];
      if (partner == kNoPartner) continue;
      const std::size_t slot = to >= from ? k : next++;
      out.partner[i * to + slot] = partner;
      for_each_history_field(out, h, [&](const char*, unsigned bit, auto& field, const auto& stored) {
        if ((kept & bit) && !stored.empty()) field[i * to + slot] = stored[i * from + k];
      });
    }
  }
  return out;
}

std::string field_names(unsigned bits) {
  std::string names;
  HostHistory h;
  for_each_history_field(h, [&](const char* name, unsigned bit, auto&) {
    if (bits & bit) names += (names.empty() ? "" : ", ") + std::string(name);
  });
  return names;
}

}  // namespace

EditedRestart adapt_to_edited_scene(RestartState& state, const std::vector<Wall>& stored_walls,
                                    const SceneSpec& scene) {
  EditedRestart report;
  check_particles(state, scene);
  check_inlets(state, scene);
  std::vector<Wall> posed;
  const std::vector<int> wall_to = match_walls(stored_walls, scene, state.time, posed);
  std::vector<bool> matched(posed.size(), false);
  for (std::size_t w = 0; w < wall_to.size(); ++w) {
    if (wall_to[w] >= 0) matched[std::size_t(wall_to[w])] = true;
    else report.gone_walls.push_back(w);
  }
  for (std::size_t k = 0; k < posed.size(); ++k)
    if (!matched[k]) report.new_walls.push_back(scene.wall_names[k]);
  check_new_walls(state, scene, posed, matched);
  check_meshes(state, scene);
  const unsigned kept = history_fields_kept(scene.model, scene.effects);
  report.slots_before = state.particles.history.slots;
  report.slots_after = kept ? scene.contact_slots : 0;
  state.particles.history = relaid(state, wall_to, report.slots_after, kept, report);
  return report;
}

std::vector<std::string> edited_restart_lines(const EditedRestart& e, std::size_t dropped, std::uint64_t stored_hash,
                                              std::uint64_t hash, const std::string& stored_text,
                                              const std::string& text, std::size_t scene_walls) {
  std::vector<std::string> lines;
  if (stored_hash == hash) {
    lines.push_back("--edited-scene: the scene is the one that wrote the checkpoint (scene hash " + hex64(hash) + ")");
    return lines;
  }
  lines.push_back("edited scene: the checkpoint was written for scene hash " + hex64(stored_hash) + ", this scene has " +
                  hex64(hash));
  if (stored_text.empty()) {
    lines.push_back("  the checkpoint does not hold its scene's text (written before 2026-12-05): edits not listed");
  } else {
    const std::vector<std::string> edits = scene_differences(stored_text, text);
    if (edits.empty()) lines.push_back("  no value changed (comments or layout only)");
    for (const std::string& edit : edits) lines.push_back("  " + edit);
  }
  std::string walls = "  walls: " + std::to_string(scene_walls - e.new_walls.size()) + " of the scene's " +
                      std::to_string(scene_walls) + " as in the checkpoint";
  if (!e.new_walls.empty()) {
    walls += "; new or moved:";
    for (const std::string& name : e.new_walls) walls += " " + scene_yaml::quoted(name);
  }
  if (!e.gone_walls.empty())
    walls += "; " + std::to_string(e.gone_walls.size()) + " of the checkpoint's walls gone, " +
             std::to_string(dropped) + " contacts with them released";
  lines.push_back(walls);
  if (e.slots_before != e.slots_after)
    lines.push_back("  contact history: " + std::to_string(e.slots_after) + " slots per particle (the checkpoint's " +
                    std::to_string(e.slots_before) + ")");
  if (e.started_fields)
    lines.push_back("  contact history: " + field_names(e.started_fields) +
                    " not in the checkpoint, starting at zero for every contact");
  return lines;
}

}  // namespace gs
