#pragma once
#include <algorithm>

#include "scene/scene.hpp"

namespace gs {

// Neighbour-list entries per particle the estimate assumes: the twelve
// neighbours of a sphere in a close-packed bed of equal spheres, all within
// the default skin (a simple-cubic bed has six, a random dense one 7-10).
constexpr double kEstimatedListEntries = 12;
// At a wider skin (scene key verlet_skin) a list covers more: the entries
// grow as the volume it reaches, the cube of (1 + skin) diameters (an
// upper bound for a close-packed bed: 54 within two diameters, 72 here).
inline double estimated_list_entries(double skin) {
  const double reach = (1 + std::max(skin, kDefaultVerletSkin)) / (1 + kDefaultVerletSkin);
  return kEstimatedListEntries * reach * reach * reach;
}

struct MemoryEstimate {
  double bytes_per_particle = 0;  // the sum of the parts below
  double field_bytes = 0;         // particle state (core/particle_fields.hpp), per particle
  double force_bytes = 0;         // force and torque, per particle
  double history_bytes = 0;       // contact history: pair entries and surface rows, per particle
  double surface_row_share = 0;   // the share of the particles with a row of surface slots
  double list_bytes = 0;          // Verlet list (offsets, references, entries) and the meshes' near lists, per particle
  // What a rebuild of the lists holds at its peak beyond what the run holds
  // between rebuilds, per particle: the largest of its phases
  // (engine/neighbour_finder.hpp), with history the kept contacts', less
  // the forces and torques, whose storage a build does without
  // (Simulation::rebuild_neighbours).
  double build_bytes = 0;
  // What an output (snapshot or checkpoint) holds beside the run, per
  // particle (engine/particle_mover_output.hpp): where the ids stay dense
  // (a scene whose particles cannot leave, on one rank) a GPU's chunk, a
  // 32nd of an fp64 vector field (0.75; at least 1 MiB in all); where they
  // need not, the order by id and its sort's keys and second buffers (4 +
  // 12; the chunks then fit in the sort's staging buffer).
  double output_bytes = 0;
  // What a restart holds until its first build has kept its contacts,
  // beyond what the run holds between rebuilds, per particle
  // (engine/particle_mover_history.hpp): the pair contacts of the
  // checkpoint's rows in the pending table (a partner id and the springs
  // each, at most twelve, and a row's offset) and each particle's origin,
  // beside a piece of the rows in transit (a 32nd) or the build's sort or
  // kept contacts (the forces waiting on the host), where the Verlet list
  // and its entries' springs are not built yet; 0 where that holds less (without history). Below a build's
  // phases: the pending contacts are at most the list's entries, and a
  // build holds the old list and its springs beside the same kept contacts.
  double restart_bytes = 0;
  // A build, an output and a restart's arrival never overlap: the largest.
  double transient_bytes() const { return std::max({build_bytes, output_bytes, restart_bytes}); }
  double cell_bytes = 0;          // the cells' offsets, while a rebuild holds the cell list
  // The CPU's alone, not in bytes_per_particle, per particle: computing each
  // pair once keeps per list entry the partner's reverse entry, a load
  // (force and torque) and a touching flag (engine/force_kernel.hpp,
  // EntryLoads), and its cell sort's keys hold the ids (64 bits: 20 bytes of
  // sort buffers where a GPU's take 12); a rebuild frees the reverse
  // entries with the old list.
  double cpu_extra_bytes = 0;
  long long cells = 0;
  double mesh_bytes = 0;          // mesh arrays and their binning (a bound, walls/mesh.hpp)
  double mesh_cells = 0;          // cells of the meshes' grids
  double mesh_entries = 0;        // bound on their (cell, triangle) entries
  double total_bytes = 0;
};

// What a run of this scene holds in device memory at its peak, by the layout
// of ParticleStore, the force arrays, the contact history and the Verlet
// list (estimated_list_entries per particle, at most twelve touching)
// between rebuilds, plus the largest phase of a rebuild (the cell list with
// the sort's buffers, in the staging buffer, or the new list's entries, and
// with history the pair history's kept contacts, each pair's by one side:
// engine/pair_keep.hpp) or
// of an output or of a restart's arrival, whichever is largest, on one rank; and
// the meshes with their binning, at the smallest cells a run uses (one
// largest diameter: the most cells). docs/PERFORMANCE.md ("Bytes per
// particle") lists the same parts.
MemoryEstimate estimate_memory(const SceneSpec& scene);

}  // namespace gs
