#pragma once
// ForceComputation over an execution policy, force precision, contact model
// and set of effects: one ForceKernel thread per owned particle
// (engine/force_kernel.hpp), or on a GPU a group of lanes per particle in a
// scene too small to fill it, over the neighbours of the run's NeighbourFinder.
#include <type_traits>
#include <vector>

#include "backend/backend.hpp"
#include "engine/at_indices.hpp"
#include "engine/contact_measure_kernel.hpp"
#include "engine/force_kernel.hpp"
#include "engine/force_computation.hpp"
#include "engine/mesh_arrays.hpp"
#include "engine/neighbour_finder.hpp"
#include "engine/pairs_once_policy.hpp"
#include "engine/step_state.hpp"
#include "engine/surface_rows.hpp"

namespace gs {

template <class Exec, class Real, class Model, unsigned Effects>
class ForceComputer final : public ForceComputation {
  static constexpr unsigned kKept = history_fields_kept<Model>(Effects);
  static constexpr bool kTorque = makes_torques(Effects);
  static constexpr bool kPairsOnce = Exec::pairs_once;  // the CPU: engine/force_kernel.hpp, pairs_of

 public:
  ForceComputer(const std::vector<MaterialSpec>& materials, const std::vector<PairSpec>& pairs, StepState<Real>& state,
                const NeighbourFinder<Exec>& neighbours)
      : pairs_(Exec::backend), walls_(Exec::backend), wall_screens_(Exec::backend), meshes_(Exec::backend),
        st_(state), neighbours_(neighbours) {
    if (state.kept != kKept || state.torque != kTorque)
      throw std::logic_error("the step state does not keep what the force computation writes");
    n_materials_ = int(materials.size());
    pairs_.from_host(make_pair_table<Real, Model>(materials, pairs));
  }

  // Every step where walls move: queued behind the last step's kernels, which
  // read the walls' previous poses, instead of waiting for them.
  void set_walls(const std::vector<Wall>& walls) override {
    walls_.from_host_queued(walls);
    std::vector<WallScreen> screens;
    for (const Wall& w : walls) screens.push_back(wall_screen(w));
    wall_screens_.from_host_queued(screens);
    n_walls_ = int(walls.size());
  }
  void set_meshes(const MeshSet& meshes) override {
    meshes_.set(meshes);
    meshes_.load.resize(0);  // no load before the first computation (a restart's too)
  }
  void set_mesh_pose(const MeshSet& meshes) override {
    for (std::int32_t m = 0; m < meshes.n_meshes(); ++m) {
      const std::int32_t begin = meshes.vertex_begin[m], end = meshes.vertex_begin[m + 1];
      Exec::parallel_for(Index(end - begin), PoseVertices{meshes.pose[m], meshes_.reference.data(),
                                                          meshes_.vertex.data(), std::size_t(begin),
                                                          meshes_.pose.data() + m});
    }
  }
  void set_mesh_bins(const MeshBins& bins) override { meshes_.set_bins(bins); }
  void build_surface_lists(const ParticleStore& s, double skin) override {
    build_mesh_near_lists(s, skin);
    if constexpr (kKept != 0) {
      // No surface, no row held: nothing to assign (and no scan to wait for).
      const ContactHistory<Real>& h = st_.history;
      if (n_walls_ == 0 && meshes_.n_triangles == 0 && h.rows == 0 && !h.row_for_every_particle) return;
      SurfaceNeed need{};
      need.position = s.position.data();
      need.radius = s.radius.data();
      need.walls = walls_.data();
      need.n_walls = n_walls_;
      need.near = near_view();
      need.skin = skin;
      assign_surface_rows<Exec>(st_.history, kKept, s.n_owned, need, st_.staging, row_scan_);
    }
  }

  void compute(ParticleStore& s, double dt, long long step) override {
    meshes_.reserve(std::size_t(s.size()));
    with_candidates(s, [&](const auto& candidates) {
      const auto k = kernel(s, candidates, dt, step);
      if constexpr (kPairsOnce) {
        if (policy_.choose(step)) {
          const EntryLoads<Real> e = entry_loads(s);
          Exec::parallel_for(s.n_owned, PairPass<decltype(k)>{k, PairsOf::all, e});
          Exec::parallel_for(s.n_owned, SumPass<decltype(k)>{k, e});
          count_touching(s, step);
          return;
        }
      }
      launch_forces(s.n_owned, k, [](const auto& f) { return f; });
    });
  }
  // Each pair once: the pairs among all the owned particles first, whichever
  // of the two is an interior one; then the interior's sums.
  void compute_interior(ParticleStore& s, double dt, long long step, const GhostSplit& split) override {
    meshes_.reserve(std::size_t(s.size()));
    with_candidates(s, [&](const auto& candidates) {
      const auto k = kernel(s, candidates, dt, step);
      if constexpr (kPairsOnce) {
        split_once_ = policy_.choose(step);  // the boundary's part goes the same way
        if (split_once_) {
          const EntryLoads<Real> e = entry_loads(s);
          Exec::parallel_for(s.n_owned, PairPass<decltype(k)>{k, PairsOf::owned, e});
          Exec::parallel_for(split.interior, AtIndices<SumPass<decltype(k)>>{{k, e}, split.order});
          return;
        }
      }
      launch_forces(split.interior, k, at_indices(split.order));
    });
  }
  // Then the pairs with ghosts, and the boundary's sums.
  void compute_boundary(ParticleStore& s, double dt, long long step, const GhostSplit& split) override {
    meshes_.reserve(std::size_t(s.size()));
    const Index* boundary = split.order + split.interior;
    with_candidates(s, [&](const auto& candidates) {
      const auto k = kernel(s, candidates, dt, step);
      if constexpr (kPairsOnce) {
        if (split_once_) {
          const EntryLoads<Real> e = entry_loads(s);
          Exec::parallel_for(split.boundary, AtIndices<PairPass<decltype(k)>>{{k, PairsOf::ghosts, e}, boundary});
          Exec::parallel_for(split.boundary, AtIndices<SumPass<decltype(k)>>{{k, e}, boundary});
          count_touching(s, step);
          return;
        }
      }
      launch_forces(split.boundary, k, at_indices(boundary));
    });
  }

  void measure_contacts(ParticleStore& s, long long step) override {
    measures_.resize(std::size_t(s.n_owned));
    with_candidates(s, [&](const auto& candidates) {
      using Candidates = std::decay_t<decltype(candidates)>;
      Exec::parallel_for(s.n_owned, ContactMeasureKernel<Real, Model, Effects, Candidates>{
                                        kernel(s, candidates, 0.0, step), measures_.data()});
    });
  }
  std::vector<ContactMeasure> contact_measures(const ParticleStore& s) const override {
    std::vector<ContactMeasure> h = measures_.to_host();
    h.resize(std::size_t(s.n_owned));
    return h;
  }

  std::vector<MeshLoad> particle_mesh_loads(const ParticleStore& s) const override {
    if (meshes_.n_triangles == 0) return {};
    const std::size_t n = std::size_t(s.n_owned) * std::size_t(meshes_.n_meshes);
    if (meshes_.load.size() < n) return std::vector<MeshLoad>(n);
    std::vector<MeshLoad> h = meshes_.load.to_host();
    h.resize(n);
    return h;
  }
  std::size_t bytes() const override {
    return pairs_.bytes() + walls_.bytes() + wall_screens_.bytes() + meshes_.bytes() + near_begin_.bytes() +
           near_triangles_.bytes() + measures_.bytes() + entry_load_.bytes() + entry_touching_.bytes();
  }

 private:
  // Calls f with the contact partners the force computation visits: the
  // Verlet list, which the step loop keeps valid (every rank rebuilds it
  // after each rebuild of its halo), or the cells where the backend keeps no
  // list.
  template <class F>
  void with_candidates(ParticleStore& s, F&& f) {
    if constexpr (Exec::verlet_list) {
      if (!neighbours_.list_valid(s)) throw std::logic_error("forces before the Verlet list was built");
      if (meshes_.n_triangles > 0 && near_built_at_ != s.revision)
        throw std::logic_error("forces before the meshes' near lists were built");
      f(neighbours_.list_candidates());
    } else {
      f(neighbours_.cell_candidates(s));
    }
  }
  // n kernel items: lane groups over a Verlet list (a group per particle in
  // a scene too small to fill the GPU), else one thread each.
  template <class F>
  void launch(Index n, const F& f) {
    if constexpr (Exec::verlet_list) Exec::parallel_for_lanes(n, lanes_setting_, f);
    else Exec::parallel_for(n, f);
  }
  // The force kernel k over n items, each the functor as(k) makes (k
  // itself, or k at a list of indices), launched as launch does; on a GPU,
  // where one thread takes a particle and the scene has no mesh, without
  // the mesh path (WithoutMeshes).
  template <class K, class As>
  void launch_forces(Index n, const K& k, const As& as) {
    if constexpr (Exec::backend == Backend::cuda) {
      if (meshes_.n_triangles == 0 && force_lanes(n, lanes_setting_) == 1)
        return Exec::parallel_for(n, as(WithoutMeshes<K>{k}));
    }
    launch(n, as(k));
  }
  static auto at_indices(const Index* index) {
    return [index](const auto& f) { return AtIndices<std::decay_t<decltype(f)>>{f, index}; };
  }
  template <class Candidates>
  ForceKernel<Real, Model, Effects, Candidates> kernel(ParticleStore& s, const Candidates& candidates, double dt,
                                                       long long step) {
    return {s.id.data(), s.material.data(), s.radius.data(), s.mass.data(), s.position.data(), s.velocity.data(),
            s.angular_velocity.data(), candidates, neighbours_.box(),
            PairTable<Real, Model>{pairs_.data(), n_materials_}, walls_.data(), wall_screens_.data(), n_walls_,
            meshes_.view(), near_view(), meshes_.loads(), st_.pairs.current.template view<kKept>(), slot_table(),
            st_.row_width, st_.forces.force.data(), kTorque ? st_.forces.torque.data() : nullptr, Real(dt),
            st_.fault.data(), step};
  }
  // The two passes of each pair once, one particle per call.
  template <class K>
  struct PairPass {
    static constexpr int kMinBlocksPerSM = K::kMinBlocksPerSM;
    K k;
    PairsOf which;
    EntryLoads<Real> e;
    GS_HD void operator()(Index i) const { k.pairs_of(i, which, e); }
  };
  template <class K>
  struct SumPass {
    static constexpr int kMinBlocksPerSM = K::kMinBlocksPerSM;
    K k;
    EntryLoads<Real> e;
    GS_HD void operator()(Index i) const { k.sum_entries(i, e); }
  };
  // Tells the policy how many list entries touch per owned particle, where it asks.
  void count_touching(const ParticleStore& s, long long step) {
    if (!policy_.counts()) return;
    const std::size_t touching = Exec::count_set(entry_touching_.data(), entry_touching_.size());
    policy_.counted(s.n_owned > 0 ? double(touching) / double(s.n_owned) : 0.0, step);
  }
  // The loads per list entry, sized to the list (each pass writes every entry it reads).
  EntryLoads<Real> entry_loads(const ParticleStore& s) {
    const VerletList& v = neighbours_.verlet();
    entry_load_.resize_discarding(v.list.size());
    entry_touching_.resize_discarding(v.list.size());
    return {entry_load_.data(), entry_touching_.data(), v.reverse.data(), s.n_owned};
  }

  // Two passes over the owned particles (count, fill) around a scan of the
  // counts, whose total comes back to the host to size the list; with as
  // many lanes per particle as the forces. The scan checks its offsets for
  // wrapping (one more wait for the device) only where the bound on the
  // lists' length does not rule it out.
  void build_mesh_near_lists(const ParticleStore& s, double skin) {
    if (meshes_.n_triangles == 0) return;
    const Index n = s.n_owned;
    near_begin_.resize_discarding(std::size_t(n) + 1);
    launch(n, MeshNearPass<false>{meshes_.view(), s.position.data(), s.radius.data(), skin, near_begin_.data(),
                                  nullptr});
    const bool bounded = double(n) * double(meshes_.near_bound) < 4294967296.0;
    const ListOffset total =
        Exec::scan_counts(near_begin_.data(), n, st_.staging, bounded ? nullptr : "the meshes' near lists");
    near_triangles_.resize_discarding(total);
    launch(n, MeshNearPass<true>{meshes_.view(), s.position.data(), s.radius.data(), skin, near_begin_.data(),
                                 near_triangles_.data()});
    near_built_at_ = s.revision;
  }

  MeshNearView near_view() const {
    if (meshes_.n_triangles == 0) return {};
    return {near_begin_.data(), near_triangles_.data()};
  }

  SlotTable<Real, kKept> slot_table() {
    ContactHistory<Real>& h = st_.history;
    SlotTable<Real, kKept> t;
    t.row = h.row.data();
    t.partner = h.partner.data();
#define GS_POINT_AT_FIELD(name, value, bit) t.name = h.name.data();
    GS_HISTORY_FIELDS(GS_POINT_AT_FIELD)
#undef GS_POINT_AT_FIELD
    t.slots = h.slots;
    t.strides = h.strides;
    return t;
  }

  DeviceArray<PairParams<Real, Model>> pairs_;
  int n_materials_ = 0;
  DeviceArray<Wall> walls_;
  DeviceArray<WallScreen> wall_screens_;  // per wall, at the pose walls_ holds
  int n_walls_ = 0;
  DeviceMeshes meshes_;
  // Per owned particle, from the last build of the neighbour lists (walls/mesh_near.hpp).
  DeviceArray<ListOffset> near_begin_{Exec::backend};
  DeviceArray<std::int32_t> near_triangles_{Exec::backend};
  std::uint64_t near_built_at_ = ~std::uint64_t(0);  // the store's revision then
  // The scan's scratch of the surface rows' build (engine/surface_rows.hpp).
  DeviceArray<unsigned char> row_scan_{Exec::backend};
  StepState<Real>& st_;
  const NeighbourFinder<Exec>& neighbours_;
  // GRAINSTORM_FORCE_LANES, read once, not at every step (the CPU has no lanes).
  int lanes_setting_ = Exec::backend == Backend::cuda ? force_lanes_setting() : 1;
  // Each pair once or each side (GRAINSTORM_PAIRS_ONCE, read once), where
  // the backend computes pairs once at all; the way of the split step in hand.
  PairsOncePolicy policy_{kPairsOnce ? pairs_once_setting() : PairsOnceSetting::never};
  bool split_once_ = false;
  DeviceArray<ContactLoad<Real>> entry_load_{Exec::backend};  // each pair once: the loads per list entry
  DeviceArray<std::uint8_t> entry_touching_{Exec::backend};
  DeviceArray<ContactMeasure> measures_{Exec::backend};  // the contact pass's, sized at its first use
};

}  // namespace gs
