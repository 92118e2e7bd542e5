#include "app/commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "engine/memory_estimate.hpp"
#include "run/driver.hpp"
#include "scene/particle_sources.hpp"
#include "scene/scene_loader.hpp"

namespace gs {

long long whole_number(const std::string& text, long long lo, long long hi, const std::string& rule) {
  std::size_t used = 0;
  long long n = 0;
  try {
    n = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || n < lo || n > hi) throw std::invalid_argument(rule + ", got '" + text + "'");
  return n;
}

int command_check(const std::vector<std::string>& args) {
  if (args.size() != 2) throw std::invalid_argument("usage: grainstorm check SCENE");
  const SceneSpec scene = load_scene(args[1]);
  print_warnings(scene);
  const MemoryEstimate m = estimate_memory(scene);
  std::printf("scene %s is valid\n", args[1].c_str());
  std::printf("particles:      %zu\n", particle_count(scene));
  std::printf("walls:          %zu\n", scene.walls.size());
  if (scene.periodic_axes != 0)
    std::printf("periodic:       %s%s%s\n", scene.periodic_axes & 1u ? "x" : "", scene.periodic_axes & 2u ? "y" : "",
                scene.periodic_axes & 4u ? "z" : "");
  std::printf("precision:      %s\n", precision_name(scene.precision));
  std::printf("contact time:   %.6g s\n", scene.contact_time);
  std::printf("time step:      %.6g s (%.4g of the contact time)\n", scene.time_step,
              scene.time_step / scene.contact_time);
  std::printf("stable limit:   %.6g s (%.4g of the contact time), set by the %s\n", scene.stable_time_step,
              scene.stable_time_step / scene.contact_time, scene.stable_step_binding.c_str());
  std::printf("steps:          %lld\n", std::llround(scene.duration / scene.time_step));
  std::printf("verlet skin:    %.4g largest diameters (%.4g m; the memory estimate counts %.1f list entries "
              "per particle)\n",
              scene.verlet_skin, 2 * largest_radius(scene) * scene.verlet_skin,
              estimated_list_entries(scene.verlet_skin));
  std::printf("memory:         %s (%.0f bytes per particle, %s for %lld cells; the CPU backend %.0f more per particle)\n",
              human_bytes(m.total_bytes).c_str(), m.bytes_per_particle, human_bytes(m.cell_bytes).c_str(),
              m.cells, m.cpu_extra_bytes);
  if (m.history_bytes > 0)
    std::printf("                %.1f %% of the particles start within reach of a wall or mesh: the estimate gives "
                "them rows of surface slots\n",
                100 * m.surface_row_share);
  if (scene.meshes.n_meshes() > 0)
    std::printf("meshes:         %d triangles, %s with their binning (%.3g cells, up to %.3g entries)\n",
                int(scene.meshes.n_triangles()), human_bytes(m.mesh_bytes).c_str(), m.mesh_cells, m.mesh_entries);
  if (const Exits exits = exits_of(scene.outlets, scene.open_faces); exits.any()) {
    std::string names;
    for (const std::string& n : exits.names) names += (names.empty() ? "" : ", ") + n;
    std::printf("exits:          %s (what leaves goes to removed.csv)\n", names.c_str());
  }
  return 0;
}

}  // namespace gs
