#include "engine/memory_estimate.hpp"

#include <algorithm>
#include <vector>

#include "contact/contact_models.hpp"
#include "core/particle_fields.hpp"
#include "engine/pair_history.hpp"
#include "neighbor/cell_grid.hpp"
#include "neighbor/verlet_list.hpp"
#include "scene/particle_sources.hpp"
#include "walls/mesh.hpp"
#include "walls/wall_geometry.hpp"

namespace gs {
namespace {

// The share of the scene's particles, as they start, that a build gives a
// row of surface slots (engine/surface_rows.hpp): within reach of a wall
// (each as posed at the start, switched on) or of the ball about a mesh's
// reference bounds (which holds it in every pose its rotation about its
// centre gives). Counted over every particle up to kCountedAll of them,
// else over kRuns evenly spread runs of kRun in id order.
double surface_row_share(const SceneSpec& scene, double skin) {
  const std::size_t n = particle_count(scene);
  if (n == 0) return 0;
  const double r = largest_radius(scene);
  std::vector<Wall> walls = scene.walls;
  for (Wall& w : walls) w.active = true;
  std::vector<Vec3d> centre;
  std::vector<double> reach;
  for (std::int32_t m = 0; m < scene.meshes.n_meshes(); ++m) {
    Vec3d lo, hi;
    mesh_reference_bounds(scene.meshes, m, lo, hi);
    centre.push_back((lo + hi) * 0.5);
    reach.push_back(0.5 * norm(hi - lo) + r + skin);
  }
  std::size_t near = 0, seen = 0;  // (the blocks come one after the other)
  auto count = [&](const std::vector<Vec3d>& block) {
    std::size_t k = 0;
    for (const Vec3d& x : block) {
      bool hit = false;
      for (const Wall& w : walls) hit = hit || wall_within_reach(w, x, r, skin);
      for (std::size_t m = 0; m < centre.size() && !hit; ++m) hit = norm(x - centre[m]) < reach[m];
      k += hit;
    }
    near += k;
    seen += block.size();
  };
  constexpr std::size_t kCountedAll = 20000000, kRuns = 64, kRun = 16384;
  if (n <= kCountedAll) {
    for_each_position_block(scene, 0, n, count);
  } else {
    for (std::size_t k = 0; k < kRuns; ++k) {
      const std::size_t first = k * (n - kRun) / (kRuns - 1);
      for_each_position_block(scene, first, first + kRun, count);
    }
  }
  return double(near) / double(seen);
}

}  // namespace

MemoryEstimate estimate_memory(const SceneSpec& scene) {
  const double real = fp32_forces(scene.precision) ? 4 : 8;
  MemoryEstimate m;
  const unsigned fields = particle_fields_kept(scene);
#define GS_ADD_FIELD(name, type, bit) \
  if ((bit) == kEveryRun || (fields & (bit)) != 0) m.field_bytes += sizeof(type);
  GS_PARTICLE_FIELDS(GS_ADD_FIELD)
#undef GS_ADD_FIELD
  m.force_bytes = 3 * real;                                   // force
  if (makes_torques(scene.effects)) m.force_bytes += 3 * real;  // torque
  const unsigned fields_kept = history_fields_kept(scene.model, scene.effects);
  const double entries = estimated_list_entries(scene.verlet_skin);
  double kept = 0;        // the kept contacts at a rebuild, per particle
  double pair_entry = 0;  // a list entry's touching flag and springs
  double springs = 0;     // one contact's history fields
  if (fields_kept != 0) {
    double largest = sizeof(ParticleId);  // the largest array of a surface table
    auto add_field = [&](double bytes) {
      springs += bytes;
      largest = std::max(largest, bytes);
    };
    const bool wide = real == 8;
#define GS_ADD_FIELD(name, value, bit) \
  if (fields_kept & (bit)) add_field(wide ? sizeof(value<double>) : sizeof(value<float>));
    GS_HISTORY_FIELDS(GS_ADD_FIELD)
#undef GS_ADD_FIELD
    // A touching flag and the springs per list entry (engine/pair_history.hpp);
    // a row's index per particle, and for the share of them near a wall or
    // mesh a row of surface slots of a partner id and the springs, with room
    // for a quarter more, and at a build the new copy of one of its arrays
    // (engine/surface_rows.hpp).
    pair_entry = sizeof(std::uint8_t) + springs;
    const double r = largest_radius(scene), skin = 2 * r * scene.verlet_skin;
    m.surface_row_share = surface_row_share(scene, skin);
    m.history_bytes = pair_entry * entries + sizeof(Index) +
                      1.25 * m.surface_row_share * (sizeof(ParticleId) + springs + largest) * scene.surface_slots;
    // Each particle's touching contacts (a partner id and the springs; at
    // most twelve touch in a close-packed bed), kept at a rebuild for the
    // new list, on one rank each pair's by one side (halved rows:
    // engine/pair_keep.hpp).
    kept = (sizeof(ParticleId) + springs) * kEstimatedListEntries / 2;
  }
  // The Verlet list between rebuilds: offsets, fp32 reference positions,
  // entries (neighbor/verlet_list.hpp).
  const double list_entries = sizeof(Index) * entries;
  m.list_bytes = sizeof(ListOffset) + sizeof(Vec3f) + list_entries;
  // With meshes, the near lists' offsets (walls/mesh_near.hpp); their
  // entries, 4 bytes per triangle near a particle, are few and left out.
  if (scene.meshes.n_meshes() > 0) m.list_bytes += sizeof(ListOffset);
  const double r = largest_radius(scene);
  if (r > 0) {
    const CellGrid g = make_cell_grid(scene.domain_min, scene.domain_max, 2 * r, periodic_box(scene));
    m.cells = g.cell_count();
    m.cell_bytes = double(sizeof(Index)) * double(m.cells + 1);  // the cells' offsets
  }
  // A rebuild's phases against what is held between rebuilds
  // (engine/neighbour_finder.hpp), each transient freed before the next
  // phase allocates. The old list's references and, without history, its
  // entries (and the CPU's reverse entries) are freed first, and the forces,
  // whose values a build inside a step has spent
  // (Simulation::rebuild_neighbours). With history the old
  // list's entries and springs become the carried table and each particle
  // gets an origin row; each particle's touching contacts are kept from it
  // (the kept contacts and their offsets) before the sort, and the carried
  // table and the origins are freed. Then the cell order of the particles
  // beside the sort's keys and second buffers, in the staging buffer (32-bit
  // keys of the cell alone, 12 bytes, on a GPU where the cells number at most
  // 2^32: neighbor/cell_list.hpp; the CPU's 64-bit keys with the ids, 20);
  // then the new list's entries beside the cell order, and, once the cell
  // list is gone, with history the new list's springs, into which the kept
  // contacts are merged. A re-sort before a build holds the forces, the
  // cell order and a gather of one fp64 component of a field in the sort's
  // buffers. (A GPU that finds the neighbours in one pass holds their rows
  // only in the room of the carried table's springs less the cells:
  // NeighbourFinder::staged_width; no phase above these.)
  const bool history = fields_kept != 0;
  const double origin = history ? sizeof(Index) : 0, order = sizeof(Index);
  auto build_peak = [&](double sort_buffers, double freed_per_entry) {
    // Freed first: the old references, without history the old entries,
    // the CPU's reverse entries.
    const double spent = sizeof(Vec3f) + (history ? 0 : list_entries) + freed_per_entry * entries;
    const double resort = -spent + origin + order + std::max(double(sizeof(double)), sort_buffers);
    const double sorting = order + sort_buffers;
    if (history) {
      const double keep = -spent - m.force_bytes + origin + sizeof(ListOffset) + kept;
      const double carried = sizeof(ListOffset) + list_entries + pair_entry * entries;  // with the origins, freed
      const double sort = keep - origin - carried + sorting;
      // the entries (and reverse entries) back
      const double merge = -double(sizeof(Vec3f)) - m.force_bytes + sizeof(ListOffset) + kept;
      return std::max({0.0, resort, keep, sort, merge});
    }
    const double sort = -spent - m.force_bytes + sorting;
    return std::max({0.0, resort, sort, -spent - m.force_bytes + order + list_entries});
  };
  // A restart before and through its first build, against what is held
  // between rebuilds: the pair contacts of the checkpoint's rows wait in the
  // pending table (a partner id and the springs each, both sides of a pair,
  // at most twelve or contact_slots; a row's offset) with each particle's
  // origin, first beside a piece of the rows in transit (a 32nd of the
  // contact_slots: engine/particle_mover_history.hpp), then beside the
  // build's kept contacts, which then stand beside its sort; the forces wait
  // on the host through the build (Simulation's restart); no list and no
  // entries exist yet.
  auto restart_peak = [&](double sort_buffers) {
    const double contact = sizeof(ParticleId) + springs;
    const double pending = std::min(double(scene.contact_slots), kEstimatedListEntries) * contact + sizeof(ListOffset);
    const double arrival = pending + origin + double(scene.contact_slots) * contact / 32;
    const double keep = pending + origin + sizeof(ListOffset) + kept - m.force_bytes;
    const double sort = sizeof(ListOffset) + kept + order + sort_buffers - m.force_bytes;
    return std::max(0.0, std::max({arrival, keep, sort}) - m.list_bytes - pair_entry * entries);
  };
  const double key = m.cells <= (std::int64_t(1) << 32) ? sizeof(std::uint32_t) : sizeof(std::uint64_t);
  m.build_bytes = build_peak(2 * key + sizeof(Index), 0);
  if (history) m.restart_bytes = restart_peak(2 * key + sizeof(Index));
  // An output's chunk (engine/output_chunk.hpp) per particle: the
  // positions' (with history a build's phase outweighs any chunk), a 32nd
  // of them but at least 1 MiB, and no more than the whole field.
  const bool ids_stay_dense = !scene.has_exits();
  const double n = double(particle_count(scene)), vector = sizeof(Vec3d);
  const double chunk = n > 0 ? std::min(vector, std::max(vector / 32, double(1 << 20) / n)) : 0;
  m.output_bytes = ids_stay_dense ? chunk : sizeof(Index) + 3 * sizeof(std::uint32_t);
  m.bytes_per_particle = m.field_bytes + m.force_bytes + m.history_bytes + m.list_bytes + m.transient_bytes();
  // The CPU's per entry: a reverse entry (freed at a rebuild), a load and a touching flag.
  const double cpu_held = sizeof(ListOffset) + 6 * real + sizeof(std::uint8_t);
  // Its output writes the host's arrays directly (no chunks), with an order
  // array where the ids need not be dense (the order itself made on the host).
  const double cpu_output = ids_stay_dense ? 0 : sizeof(Index);
  const double cpu_build = build_peak(2.0 * sizeof(std::uint64_t) + sizeof(Index), sizeof(ListOffset));
  const double cpu_phase = cpu_held * entries + std::max(cpu_build, cpu_output);
  // Through a restart's first build the CPU holds what a GPU does (no list,
  // no entries) but for its wider sort keys.
  const double cpu_restart = history ? restart_peak(2.0 * sizeof(std::uint64_t) + sizeof(Index)) : 0;
  m.cpu_extra_bytes = std::max(cpu_phase, cpu_restart) - m.transient_bytes();
  const MeshSet& meshes = scene.meshes;
  if (r > 0 && meshes.n_meshes() > 0) {
    const double skin = 2 * r * scene.verlet_skin;
    const MeshBinningSize bins = binning_size(meshes, 2 * r + skin, run_binning(2 * r + skin, skin));
    m.mesh_cells = bins.total_cells();
    m.mesh_entries = bins.total_entries();
    // Per vertex the reference and current pose; per triangle corners, edges,
    // ownership and mesh id; per edge its ends.
    m.mesh_bytes = bins.bytes() + 48.0 * meshes.n_vertices() + 29.0 * meshes.n_triangles() + 8.0 * meshes.n_edges;
  }
  m.total_bytes = m.bytes_per_particle * double(particle_count(scene)) + m.cell_bytes + m.mesh_bytes;
  return m;
}

}  // namespace gs
