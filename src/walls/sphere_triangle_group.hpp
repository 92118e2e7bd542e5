#pragma once
// for_each_mesh_contact (walls/sphere_triangle.hpp) by a group of lanes that
// share one sphere (engine/force_kernel.hpp, in_group): the lanes test the
// cell's triangles g.size at a time, and the rule's reports likewise; the
// contacts, the same as for_each_mesh_contact finds, in the same order, are
// visited on lane 0 alone. A Group has `size` and `rank` (0 for the leader),
// leader(), ballot(bool): the lanes' votes as bits 0..size-1, on every lane,
// and shuffle(v, from): lane `from`'s v (backend/cuda/lane_group.cuh).
#include "core/bits.hpp"
#include "walls/mesh_near.hpp"
#include "walls/sphere_triangle.hpp"

namespace gs {

// The nearest report over the group (each lane's own, on entry), on every lane.
template <class Group>
GS_HD void nearest_over_group(const Group& g, NearestReport& nearest) {
  for (int step = 1; step < g.size; step <<= 1) {
    const int from = g.rank ^ step;
    const double distance = g.shuffle(nearest.distance, from);
    const std::uint8_t feature = std::uint8_t(g.shuffle(int(nearest.feature), from));
    const std::int32_t t = g.shuffle(nearest.t, from);
    if (t >= 0) nearest.consider(distance, feature, t);
  }
}

template <class Group, class Visitor>
GS_HD void for_each_mesh_contact_in_group(const MeshView& m, const std::int32_t* list, std::int32_t count,
                                          const Vec3d& x, double radius, const Group& g, Visitor& visit) {
  // The triangles within reach, as for_each_mesh_contact_in lists them; each
  // lane keeps the same copy.
  std::int32_t in_reach[kMeshInReachCap];
  std::int32_t n_in_reach = 0;
  NearestReport nearest;  // of this lane's triangles, then of the group's
  for (std::int32_t first = 0; first < count; first += g.size) {
    const std::int32_t k = first + g.rank;
    bool near = false;
    if (k < count) {
      const ClosestPoint r = triangle_closest_point(m, list[k], x);
      near = r.distance < radius;
      if (near) nearest.consider(r.distance, r.feature, list[k]);
    }
    for (unsigned hits = g.ballot(near); hits != 0; hits &= hits - 1) {
      if (n_in_reach < kMeshInReachCap) in_reach[n_in_reach] = list[first + lowest_bit(hits)];
      ++n_in_reach;
    }
  }
  nearest_over_group(g, nearest);
  if (n_in_reach <= kMeshInReachCap) {
    list = in_reach;
    count = n_in_reach;
  }
  const double tol = mesh_coincidence_tolerance(x, radius);
  const double tol2 = tol * tol;
  for (std::int32_t first = 0; first < count; first += g.size) {
    const std::int32_t k = first + g.rank;
    bool kept = false;
    if (k < count)
      kept = mesh_report_kept(m, list, count, x, radius, tol2, list[k], triangle_closest_point(m, list[k], x),
                              nearest.t);
    unsigned keep = g.ballot(kept);
    if (!g.leader()) continue;
    for (; keep != 0; keep &= keep - 1) {
      const std::int32_t t = list[first + lowest_bit(keep)];
      visit(mesh_contact(m, t, triangle_closest_point(m, t, x), x, radius));
    }
  }
}

// The same over the binned cell of x in each mesh, as for_each_mesh_contact.
template <class Group, class Visitor>
GS_HD void for_each_mesh_contact_in_group(const MeshView& m, const Vec3d& x, double radius, const Group& g,
                                          Visitor& visit) {
  for (std::int32_t k = 0; k < m.n_meshes; ++k) {
    if (!m.pose[k].active) continue;
    std::int32_t begin, end;
    m.cell_range(k, x, begin, end);
    if (end > begin) for_each_mesh_contact_in_group(m, m.cell_triangles + begin, end - begin, x, radius, g, visit);
  }
}

// The same over a near list (walls/mesh_near.hpp), as for_each_near_mesh_contact.
template <class Group, class Visitor>
GS_HD void for_each_near_mesh_contact_in_group(const MeshView& m, const std::int32_t* list, std::int32_t count,
                                               const Vec3d& x, double radius, const Group& g, Visitor& visit) {
  for (std::int32_t first = 0, end; first < count; first = end) {
    end = mesh_run_end(m, list, count, first);
    if (m.pose[m.mesh[list[first]]].active)
      for_each_mesh_contact_in_group(m, list + first, end - first, x, radius, g, visit);
  }
}

}  // namespace gs
