#pragma once
// The triangles near each particle: counted and listed at every build of the
// neighbour lists, so that a step tests a particle against the few triangles
// that can touch it before the next build instead of its mesh cell's whole
// list (docs/MESHES.md, "Near lists"). Particle i's are
// triangles[begin[i] .. begin[i + 1]), ascending: every triangle of any mesh
// (active or not) within near_reach(r_i, skin) of the particle where it was,
// the mesh posed as it was, at the build.
//
// Why that is enough until the next build: a triangle that touches the
// particle later is within its radius then. Since the build the particle has
// moved at most half the skin (the Verlet list's rule) and every point of the
// mesh at most half the skin (mesh_displacement_bound: a build is due
// before it would be more), so at the build it was within r + skin.
#include <cstdint>

#include "core/bits.hpp"
#include "core/hd.hpp"
#include "core/one_lane.hpp"
#include "core/types.hpp"
#include "core/vec3.hpp"
#include "neighbor/verlet_list.hpp"
#include "walls/mesh.hpp"
#include "walls/sphere_triangle.hpp"

namespace gs {

// The reach of a sphere's near list (run_binning bins for the largest).
GS_HD GS_INLINE double near_reach(double radius, double skin) { return (radius + skin) * (1 + kMeshNearSlack); }

// What a kernel reads: null `begin` where the run keeps no near lists (the
// scene has no mesh).
struct MeshNearView {
  const ListOffset* begin = nullptr;  // per owned particle + 1
  const std::int32_t* triangles = nullptr;
};

// One pass of the build over particle i: the count into begin[i + 1] (Fill
// false; item 0 also sets begin[0] = 0), or the triangles into their places
// after the scan of the counts (Fill true). The mesh bins must reach
// near_reach of the largest radius (run_binning with the run's skin). On a
// GPU a small scene gives each particle a group of lanes (in_group), as its
// force kernel does: one thread per sphere scanned a cell of the impeller's
// hub, a hundred triangles, for 90 us of mixer case a's passes of 7,680.
// Elsewhere a particle is one lane's.
template <bool Fill>
struct MeshNearPass {
  static constexpr int kMinBlocksPerSM = 4;  // a launch hint, as the force kernel's
  MeshView meshes;
  const Vec3d* position;
  const float* radius;
  double skin;
  ListOffset* begin;
  std::int32_t* triangles;  // Fill only
  GS_HD void operator()(Index i) const { in_group(i, OneLane{}); }

  // The same by the lanes of g (backend/cuda/lane_group.cuh): lane r tests
  // the cell's triangles r, r + g.size, ...; the near ones of each round are
  // written in cell order, after those of the lanes before them.
  template <class Group>
  GS_HD void in_group(Index i, const Group& g) const {
    const Vec3d x = position[i];
    const double reach = near_reach(double(radius[i]), skin);
    ListOffset k = Fill ? begin[i] : 0;
    for (std::int32_t m = 0; m < meshes.n_meshes; ++m) {
      std::int32_t first, end;
      meshes.cell_range(m, x, first, end);
      for (std::int32_t round = first; round < end; round += g.size) {
        const std::int32_t c = round + g.rank;
        const bool near = c < end && triangle_closest_point(meshes, meshes.cell_triangles[c], x).distance <= reach;
        const unsigned votes = g.ballot(near);
        if constexpr (Fill) {
          if (near) triangles[k + bit_count(votes & ((1u << g.rank) - 1u))] = meshes.cell_triangles[c];
        }
        k += ListOffset(bit_count(votes));
      }
    }
    if constexpr (!Fill) {
      if (g.leader()) {
        if (i == 0) begin[0] = 0;
        begin[i + 1] = k;
      }
    }
  }
};

// The end of the run of entries list[first..) on one mesh (a near list
// holds each mesh's triangles together, meshes in order).
GS_HD GS_INLINE std::int32_t mesh_run_end(const MeshView& m, const std::int32_t* list, std::int32_t count,
                                          std::int32_t first) {
  const std::int32_t mesh = m.mesh[list[first]];
  std::int32_t end = first + 1;
  while (end < count && m.mesh[list[end]] == mesh) ++end;
  return end;
}

// The contacts of the sphere (x, radius) with the near list
// list[0..count) (ascending, holding every triangle within radius of x), as
// for_each_mesh_contact over its cells: mesh by mesh, the inactive ones
// skipped, each mesh's contacts in ascending triangle order.
// (walls/sphere_triangle_group.hpp: the same by a group of lanes.)
template <class Visitor>
GS_HD void for_each_near_mesh_contact(const MeshView& m, const std::int32_t* list, std::int32_t count, const Vec3d& x,
                                      double radius, Visitor& visit) {
  for (std::int32_t first = 0, end; first < count; first = end) {
    end = mesh_run_end(m, list, count, first);
    if (m.pose[m.mesh[list[first]]].active) for_each_mesh_contact_in(m, list + first, end - first, x, radius, visit);
  }
}

}  // namespace gs
