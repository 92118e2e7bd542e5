// The device layout of meshes (edge numbering, feature ownership) and the
// binning of triangles into a cell grid per mesh in its reference pose (CSR,
// ascending lists), checked against brute force in the reference pose and
// in a moved one.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "mesh_test_helpers.hpp"
#include "walls/impeller.hpp"

namespace gs {
namespace {

MeshSet two_mesh_set() {
  MeshSet set;
  add_mesh(set, make_impeller(), 0, rotation_at_rpm(Vec3d(), Vec3d(0, 0, 1), 30));
  const test::FlatSquare floor =
      test::make_flat_square(6, 0.02, 0.2, test::Rotation(Vec3d(0, 0, 1), 0.3), Vec3d(-0.06, -0.06, -0.004), 9);
  add_mesh(set, floor.mesh, 1);
  return set;
}

TEST(MeshLayout, EdgesAndOwnership) {
  const MeshSet set = two_mesh_set();
  ASSERT_EQ(set.n_meshes(), 2);
  EXPECT_EQ(set.triangle_begin.back(), set.n_triangles());
  EXPECT_EQ(set.vertex_begin.back(), set.n_vertices());
  // Edge ids: one per distinct vertex pair, shared by the triangles using it.
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> id_of;
  std::vector<int> edge_owners(std::size_t(set.n_edges), 0), vertex_owners(std::size_t(set.n_vertices()), 0);
  std::vector<std::int32_t> first_user(std::size_t(set.n_vertices()), -1);
  for (std::int32_t t = 0; t < set.n_triangles(); ++t) {
    EXPECT_EQ(set.mesh[t], t < set.triangle_begin[1] ? 0 : 1);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = set.corners[t].v[k], b = set.corners[t].v[(k + 1) % 3];
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto [it, added] = id_of.emplace(key, set.edges[t].e[k]);
      EXPECT_EQ(it->second, set.edges[t].e[k]);
      if (added) {
        EXPECT_TRUE(set.owned[t] & (kOwnsEdge0 << k)) << "first user owns the edge";
      }
      edge_owners[set.edges[t].e[k]] += (set.owned[t] >> k) & 1;
      vertex_owners[a] += (set.owned[t] >> (3 + k)) & 1;
      if (first_user[a] < 0) first_user[a] = t;
      EXPECT_EQ(bool(set.owned[t] & (kOwnsVertex0 << k)), first_user[a] == t);
    }
  }
  EXPECT_EQ(std::int32_t(id_of.size()), set.n_edges);
  ASSERT_EQ(std::int32_t(set.edge_ends.size()), set.n_edges);
  for (const auto& [ends, id] : id_of) {
    EXPECT_EQ(set.edge_ends[id].v[0], ends.first);
    EXPECT_EQ(set.edge_ends[id].v[1], ends.second);
  }
  for (int n : edge_owners) EXPECT_EQ(n, 1);
  for (int n : vertex_owners) EXPECT_EQ(n, 1);
  // The impeller's edges are numbered first, as many as its topology has.
  std::set<std::int32_t> impeller_edges;
  for (std::int32_t t = 0; t < set.triangle_begin[1]; ++t)
    for (int k = 0; k < 3; ++k) impeller_edges.insert(set.edges[t].e[k]);
  EXPECT_EQ(impeller_edges.size(), mesh_topology(make_impeller()).edges);
  EXPECT_EQ(*impeller_edges.rbegin() + 1, std::int32_t(impeller_edges.size()));
}

// Brute force: cells of mesh m's grid overlapped by each of its triangles'
// bounding boxes (reference pose) inflated by `reach`.
std::vector<std::vector<std::int32_t>> brute_force_bins(const MeshSet& set, std::int32_t m, const CellGrid& grid,
                                                        double reach) {
  std::vector<std::vector<std::int32_t>> cells(std::size_t(grid.cell_count()));
  for (std::int32_t t = set.triangle_begin[m]; t < set.triangle_begin[m + 1]; ++t) {
    Vec3d lo(1e300, 1e300, 1e300), hi(-1e300, -1e300, -1e300);
    for (int k = 0; k < 3; ++k) {
      const Vec3d x = set.reference[set.corners[t].v[k]];
      lo = Vec3d(std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z));
      hi = Vec3d(std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z));
    }
    for (int z = 0; z < grid.dims[2]; ++z)
      for (int y = 0; y < grid.dims[1]; ++y)
        for (int x = 0; x < grid.dims[0]; ++x) {
          const Vec3d c0 = grid.origin + Vec3d(x, y, z) * grid.cell_size, c1 = c0 + Vec3d(1, 1, 1) * grid.cell_size;
          // Cells are half open [c0, c1).
          auto overlaps = [&](double l, double h, double a0, double a1) { return l - reach < a1 && h + reach >= a0; };
          if (overlaps(lo.x, hi.x, c0.x, c1.x) && overlaps(lo.y, hi.y, c0.y, c1.y) && overlaps(lo.z, hi.z, c0.z, c1.z))
            cells[std::size_t(grid.linear({x, y, z}))].push_back(t);
        }
  }
  return cells;
}

std::vector<std::int32_t> cell_list(const MeshBins& bins, std::int64_t k) {
  return std::vector<std::int32_t>(bins.triangles.begin() + bins.cell_begin[k],
                                   bins.triangles.begin() + bins.cell_begin[k + 1]);
}

// Every triangle of any mesh binned near x (the union of the meshes' lists).
std::set<std::int32_t> listed_near(const MeshView& view, const Vec3d& x) {
  std::set<std::int32_t> listed;
  for (std::int32_t m = 0; m < view.n_meshes; ++m) {
    std::int32_t begin, end;
    view.cell_range(m, x, begin, end);
    listed.insert(view.cell_triangles + begin, view.cell_triangles + end);
  }
  return listed;
}

TEST(MeshBinning, BoundingBoxBinsMatchBruteForce) {
  const MeshSet set = two_mesh_set();
  BinningOptions o;
  o.reach = 0.0015;
  o.prune_by_distance = false;
  const MeshBins bins = bin_triangles(set, 0.0071, o);
  ASSERT_EQ(bins.grid.size(), 2u);
  ASSERT_EQ(bins.cell_begin.size(), std::size_t(bins.first_cell.back()) + 1);
  EXPECT_EQ(bins.cell_begin.front(), 0);
  EXPECT_EQ(std::size_t(bins.cell_begin.back()), bins.triangles.size());
  for (std::int32_t m = 0; m < 2; ++m) {
    const CellGrid& grid = bins.grid[std::size_t(m)];
    EXPECT_EQ(bins.first_cell[m + 1] - bins.first_cell[m], grid.cell_count());
    const auto brute = brute_force_bins(set, m, grid, o.reach);
    for (std::int64_t c = 0; c < grid.cell_count(); ++c) {
      const std::vector<std::int32_t> list = cell_list(bins, bins.first_cell[m] + c);
      EXPECT_TRUE(std::is_sorted(list.begin(), list.end()));
      EXPECT_TRUE(std::adjacent_find(list.begin(), list.end()) == list.end());
      EXPECT_EQ(list, brute[std::size_t(c)]) << "mesh " << m << " cell " << c;
    }
  }
}

TEST(MeshBinning, EveryTriangleInReachIsListedAndPruningOnlyDrops) {
  const MeshSet set = two_mesh_set();
  const double reach = 0.0011;
  BinningOptions full{reach, false}, pruned{reach, true};
  const MeshBins a = bin_triangles(set, 2 * reach, full), b = bin_triangles(set, 2 * reach, pruned);
  // The blades (the impeller's last 4 x 12 triangles) are large and slanted:
  // most cells of their bounding boxes are far from them.
  const std::int32_t blades_begin = set.triangle_begin[1] - 48, blades_end = set.triangle_begin[1];
  auto blade_entries = [&](const MeshBins& bins) {
    return std::count_if(bins.triangles.begin(), bins.triangles.end(),
                         [&](std::int32_t t) { return t >= blades_begin && t < blades_end; });
  };
  EXPECT_LT(3 * blade_entries(b), blade_entries(a));
  EXPECT_LT(b.triangles.size(), a.triangles.size());
  ASSERT_EQ(a.first_cell, b.first_cell);
  for (std::int64_t c = 0; c < a.first_cell.back(); ++c)
    EXPECT_TRUE(std::includes(a.triangles.begin() + a.cell_begin[c], a.triangles.begin() + a.cell_begin[c + 1],
                              b.triangles.begin() + b.cell_begin[c], b.triangles.begin() + b.cell_begin[c + 1]));
  // Random points near the surfaces: every triangle within reach is in the list.
  const MeshView view = with_bins(set.view(), b);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<std::int32_t> pick(0, set.n_triangles() - 1);
  std::normal_distribution<double> jitter(0, reach);
  int checked = 0;
  for (int i = 0; i < 4000; ++i) {
    const MeshCorners& t = set.corners[pick(rng)];
    const Vec3d x = (set.vertex[t.v[0]] + set.vertex[t.v[1]] + set.vertex[t.v[2]]) * (1.0 / 3) +
                    Vec3d(jitter(rng), jitter(rng), jitter(rng)) + (set.vertex[t.v[0]] - set.vertex[t.v[1]]) * 0.3;
    const std::set<std::int32_t> listed = listed_near(view, x);
    for (std::int32_t u = 0; u < set.n_triangles(); ++u) {
      const ClosestPoint cp = triangle_closest_point(set.view(), u, x);
      if (cp.distance <= reach) {
        ++checked;
        EXPECT_TRUE(listed.count(u)) << "triangle " << u << " at " << cp.distance << " not listed";
      }
    }
  }
  EXPECT_GT(checked, 2000);
  // Far from every mesh, nothing is listed.
  EXPECT_TRUE(listed_near(view, Vec3d(1, 1, 1)).empty());
}

// Bins are made once, in the reference pose; a particle is looked up at its
// position carried back into each mesh's reference pose. At the start and
// with the impeller turned by 66.6 degrees, binned contacts equal the
// contacts over all triangles of the current pose.
TEST(MeshBinning, BinnedContactsEqualContactsOverAllTrianglesInAnyPose) {
  MeshSet set = two_mesh_set();
  const double radius = 0.0009;
  const MeshBins bins = bin_triangles(set, 2 * radius, BinningOptions{radius, true});
  for (const double t : {0.0, 0.37}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    move_meshes(set, t);
    const MeshView view = with_bins(set.view(), bins);
    std::mt19937_64 rng(8);
    std::uniform_int_distribution<std::int32_t> pick(0, set.n_triangles() - 1);
    std::normal_distribution<double> jitter(0, radius);
    int touching = 0;
    for (int i = 0; i < 3000; ++i) {
      const MeshCorners& c = set.corners[pick(rng)];
      const Vec3d x = set.vertex[c.v[i % 3]] + Vec3d(jitter(rng), jitter(rng), jitter(rng));
      std::vector<MeshContact> binned;
      auto collect = [&](const MeshContact& k) { binned.push_back(k); };
      for_each_mesh_contact(view, x, radius, collect);
      const std::vector<MeshContact> all = test::all_contacts(set, x, radius);
      ASSERT_EQ(binned.size(), all.size());
      touching += !all.empty();
      for (std::size_t k = 0; k < all.size(); ++k) {
        EXPECT_EQ(binned[k].triangle, all[k].triangle);
        EXPECT_EQ(binned[k].feature_key, all[k].feature_key);
        EXPECT_EQ(binned[k].overlap, all[k].overlap);
        EXPECT_EQ(binned[k].mesh, set.mesh[all[k].triangle]);
      }
    }
    EXPECT_GT(touching, 1500);
  }
}

TEST(MeshBinning, RejectsNegativeReach) {
  const MeshSet set = two_mesh_set();
  EXPECT_THROW(bin_triangles(set, 0.01, BinningOptions{-1, true}), std::invalid_argument);
}

// binning_size bounds what bin_triangles builds, for any cell size and both
// binnings: the same cells, and at least as many entries per mesh as the
// binning holds. For large triangles the Steiner bound stays within a small
// factor of the truth (a flat sheet fills ~2.7 cells of thickness, the bound 4.5).
TEST(MeshBinning, SizeBoundsTheBinning) {
  const MeshSet set = two_mesh_set();
  for (const double h : {0.0007, 0.0019, 0.0071, 0.03}) {
    for (const bool prune : {false, true}) {
      const BinningOptions o = prune ? run_binning(h, 0) : BinningOptions{0.5 * h, false};
      const MeshBins bins = bin_triangles(set, h, o);
      const MeshBinningSize size = binning_size(set, h, o);
      for (std::int32_t m = 0; m < set.n_meshes(); ++m) {
        const double cells = double(bins.first_cell[m + 1] - bins.first_cell[m]);
        const double entries = double(bins.cell_begin[bins.first_cell[m + 1]] - bins.cell_begin[bins.first_cell[m]]);
        EXPECT_EQ(size.cells[std::size_t(m)], cells) << "h " << h << " mesh " << m;
        EXPECT_GE(size.entries[std::size_t(m)], entries) << "h " << h << " mesh " << m << " prune " << prune;
        if (prune && h < 0.001) {
          EXPECT_LT(size.entries[std::size_t(m)], 4 * entries) << "h " << h << " mesh " << m;
        }
      }
      EXPECT_DOUBLE_EQ(size.bytes(), 4 * (size.total_cells() + 1 + size.total_entries()));
    }
  }
}

// A mesh in millimetres read as metres is refused before the binning
// allocates or counts anything: 300 m in cells of 2 mm.
TEST(MeshBinning, RefusesAHugeBinningBeforeAllocating) {
  TriangleMeshBuilder b("plate");
  b.quad(b.vertex({-100, -100, 0}), b.vertex({200, -100, 0}), b.vertex({200, 200, 0}), b.vertex({-100, 200, 0}));
  MeshSet set;
  add_mesh(set, b.take());
  const MeshBinningSize size = binning_size(set, 0.002, run_binning(0.002, 0));
  EXPECT_GT(size.cells[0], kMaxGridCells);
  EXPECT_GT(size.entries[0], 2e10);  // ~2.7 x (300 / 0.002)^2
  try {
    bin_triangles(set, 0.002, run_binning(0.002, 0));
    ADD_FAILURE() << "not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 'plate' needs"), std::string::npos) << e.what();
  }
  // A small grid with many entries: 1000 stacked 1 m sheets, 1 um apart, in
  // cells of 1 mm: 3e6 cells, but ~2.7e9 entries (more than 2^31 - 1), which
  // the binning used to count one by one for minutes before refusing.
  TriangleMeshBuilder stack("stack");
  for (int k = 0; k < 1000; ++k) {
    const double z = 1e-6 * k;
    stack.quad(stack.vertex({0, 0, z}), stack.vertex({1, 0, z}), stack.vertex({1, 1, z}), stack.vertex({0, 1, z}));
  }
  MeshSet stacked;
  add_mesh(stacked, stack.take());
  const MeshBinningSize stacked_size = binning_size(stacked, 0.001, run_binning(0.001, 0));
  EXPECT_LT(stacked_size.cells[0], 4e6);
  EXPECT_GT(stacked_size.entries[0], kMaxBinEntries);
  try {
    bin_triangles(stacked, 0.001, run_binning(0.001, 0));
    ADD_FAILURE() << "not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("up to"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gs
