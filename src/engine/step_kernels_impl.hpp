#pragma once
// The per-step kernels, written once over an execution policy `Exec` (CpuExec
// or CudaExec), which only decides who runs each per-particle functor and how
// keys are sorted.
#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "engine/force_kernel.hpp"
#include "engine/mesh_arrays.hpp"
#include "engine/step_kernels.hpp"
#include "neighbor/cell_list.hpp"

namespace gs {

template <class T>
struct Gather {
  const T* from;
  T* to;
  const Index* order;
  GS_HD void operator()(Index k) const { to[k] = from[order[k]]; }
};

// Occupied history slots of particle i.
struct CountContacts {
  const ParticleId* partner;
  HistoryStrides strides;
  int slots;
  std::uint16_t* count;
  GS_HD void operator()(Index i) const {
    unsigned c = 0;
    for (int k = 0; k < slots; ++k) c += partner[strides.at(k, std::size_t(i))] != kNoPartner;
    count[i] = std::uint16_t(c);
  }
};

// Whether particle i has a stored contact on an analytic wall.
struct TouchesWall {
  const ParticleId* partner;
  HistoryStrides strides;
  int slots;
  GS_HD bool operator()(Index i) const {
    for (int k = 0; k < slots; ++k) {
      const ParticleId p = partner[strides.at(k, std::size_t(i))];
      if (p >= kWallPartnerBase && p != kNoPartner) return true;
    }
    return false;
  }
};

// Marker by side of a plane: front where (x - point) . normal >= 0.
struct MarkByPlane {
  const Vec3d* position;
  std::uint8_t* marker;
  Vec3d point, normal;
  std::uint8_t front, back;
  GS_HD void operator()(Index i) const { marker[i] = dot(position[i] - point, normal) >= 0 ? front : back; }
};

template <class Exec, class Real, class Model, unsigned Effects>
class StepKernelsImpl final : public StepKernels {
  // The history fields this run keeps (core/particle_fields.hpp).
  static constexpr unsigned kKept = history_fields_kept<Model>(Effects);
  static constexpr bool kHistory = kKept != 0;
  static constexpr bool kTorque = makes_torques(Effects);

 public:
  StepKernelsImpl(const std::vector<MaterialSpec>& materials, const std::vector<PairSpec>& pairs, int slots)
      : pairs_(Exec::backend), walls_(Exec::backend), wall_screens_(Exec::backend), meshes_(Exec::backend),
        fault_(Exec::backend, 1), cells_(Exec::backend) {
    n_materials_ = int(materials.size());
    pairs_.from_host(make_pair_table<Real, Model>(materials, pairs));
    fault_.zero();
    history_.slots = kHistory ? slots : 0;
    history_.partner = DeviceArray<ParticleId>(Exec::backend);
    for_each_history_field(history_, [](const char*, unsigned, auto& a) { a = std::decay_t<decltype(a)>(Exec::backend); });
    forces_.force = DeviceArray<Vec3<Real>>(Exec::backend);
    forces_.torque = DeviceArray<Vec3<Real>>(Exec::backend);
  }

  void reserve(Index n) override {
    forces_.force.resize(n);
    if (kTorque) forces_.torque.resize(n);
    // Geometric growth, as DeviceArray's: ranks append ghosts every step, and
    // growing to the exact size re-laid the whole history (through the host)
    // at every new maximum of owned + ghosts: 90 ms per step in the mixer's
    // case c on two ranks.
    if (kHistory && std::size_t(n) > history_.capacity)
      grow_history(std::max(std::size_t(n), history_.capacity + history_.capacity / 4));
    meshes_.reserve(std::size_t(n));
  }

  void set_walls(const std::vector<Wall>& walls) override {
    walls_.from_host(walls);
    std::vector<WallScreen> screens;
    for (const Wall& w : walls) screens.push_back(wall_screen(w));
    wall_screens_.from_host(screens);
    n_walls_ = int(walls.size());
  }
  void set_meshes(const MeshSet& meshes) override {
    meshes_.set(meshes);
    meshes_.reserve(forces_.force.size());
    meshes_.load.zero();
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

  void kick_drift(ParticleStore& s, const IntegrationParams& p) override {
    KickDrift<Real> f{half_kick(s, p), s.position.data(), s.orientation.data(), s.id.data(), p,
                      fault_.data()};
    Exec::parallel_for(s.n_owned, f);
  }

  void kick(ParticleStore& s, const IntegrationParams& p) override {
    Exec::parallel_for(s.n_owned, half_kick(s, p));
  }

  void build_cell_list(ParticleStore& s, const CellGrid& grid) override {
    build_cells<Exec>(cells_, s.position.data(), s.id.data(), s.size(), grid);
    verlet_.valid = false;
  }
  bool uses_verlet_list() const override { return Exec::verlet_list; }
  void build_neighbours(ParticleStore& s, const CellGrid& grid, double skin) override {
    build_cell_list(s, grid);
    if constexpr (Exec::verlet_list)
      build_verlet_list<Exec>(verlet_, cells_, s.position.data(), s.radius.data(), s.id.data(), s.n_owned, s.size(),
                              skin);
  }
  void build_neighbours_for_one_step(ParticleStore& s, const CellGrid& grid) override { build_cell_list(s, grid); }
  bool neighbours_stale(const ParticleStore& s) const override {
    if constexpr (Exec::verlet_list) return verlet_list_stale<Exec>(verlet_, s.position.data(), s.n_owned, s.size());
    return true;
  }

  void compute_forces(ParticleStore& s, double dt, long long step) override {
    if constexpr (Exec::verlet_list) {
      if (verlet_.valid) {
        launch_forces(s, verlet_.candidates(), dt, step);
      } else {
        // build_neighbours_for_one_step: the cells of the whole store.
        if (cells_.sorted.size() != std::size_t(s.size()))
          throw std::logic_error("compute_forces before build_neighbours");
        launch_forces(s, TouchingInIdOrder{cell_candidates(), s.position.data(), s.radius.data(), s.id.data(),
                                           fault_.data(), step},
                      dt, step);
      }
    } else {
      launch_forces(s, cell_candidates(), dt, step);
    }
  }

  void mark_by_plane(ParticleStore& s, const MarkingSpec& m) override {
    Exec::parallel_for(s.n_owned, MarkByPlane{s.position.data(), s.marker.data(), m.point, m.normal, m.front, m.back});
  }

  void reorder_by_cells(ParticleStore& s) override;

  Fault take_fault() override {
    Fault f = fault_.to_host()[0];
    if (f.code != kFaultNone) fault_.zero();
    return f;
  }
  void synchronize() override { Exec::synchronize(); }

  std::vector<Vec3d> forces(const ParticleStore& s) const override { return widen(forces_.force, s.n_owned); }
  std::vector<Vec3d> torques(const ParticleStore& s) const override {
    if (!kTorque) return std::vector<Vec3d>(s.n_owned);
    return widen(forces_.torque, s.n_owned);
  }
  HostHistory history(const ParticleStore& s) const override;
  std::vector<std::uint16_t> contact_counts(const ParticleStore& s) const override;
  ParticleRecords wall_contact_history(const ParticleStore& s) const override;
  std::vector<MeshLoad> particle_mesh_loads(const ParticleStore& s) const override {
    if (meshes_.n_triangles == 0) return {};
    std::vector<MeshLoad> h = meshes_.load.to_host();
    h.resize(std::size_t(s.n_owned) * std::size_t(meshes_.n_meshes));
    return h;
  }
  MessageHeader pack(const ParticleStore& s, const DeviceArray<Index>& which, bool with_history,
                     DeviceArray<unsigned char>& out) const override;
  void unpack(ParticleStore& s, const MessageHeader& h, const unsigned char* payload, bool as_ghosts) override;
  void keep_owned(ParticleStore& s, const DeviceArray<Index>& keep) override;
  void append(ParticleStore& s, const ParticleRecords& r, bool as_ghosts) override;
  void set_forces(const ParticleStore& s, const std::vector<Vec3d>& force, const std::vector<Vec3d>& torque) override {
    forces_.force.from_host(narrowed(force, s.n_owned));
    if (kTorque) forces_.torque.from_host(narrowed(torque, s.n_owned));
    reserve(s.size());
    meshes_.load.zero();  // a restart reports no mesh load before its first step
  }
  void set_history(const ParticleStore& s, const HostHistory& h) override;

  std::size_t bytes() const override {
    std::size_t history = history_.partner.bytes();
    for_each_history_field(history_, [&](const char*, unsigned, const auto& a) { history += a.bytes(); });
    return forces_.force.bytes() + forces_.torque.bytes() + history + cells_.bytes() + verlet_.bytes() + pairs_.bytes() + walls_.bytes() + wall_screens_.bytes() +
           staging_.bytes();
  }

 private:
  CellCandidates cell_candidates() const { return {cells_.grid, cells_.sorted.data(), cells_.cell_begin.data()}; }
  template <class Candidates>
  void launch_forces(ParticleStore& s, const Candidates& candidates, double dt, long long step) {
    ForceKernel<Real, Model, Effects, Candidates> k{s.id.data(), s.material.data(), s.radius.data(), s.mass.data(),
                                                    s.position.data(), s.velocity.data(),
                                                    s.angular_velocity.data(), candidates,
                                                    PairTable<Real, Model>{pairs_.data(), n_materials_}, walls_.data(),
                                                    wall_screens_.data(), n_walls_, meshes_.view(), meshes_.loads(),
                                                    slot_table(), forces_.force.data(),
                                                    kTorque ? forces_.torque.data() : nullptr, Real(dt),
                                                    fault_.data(), step};
    Exec::parallel_for(s.n_owned, k);
  }
  // What a message of `count` particles carries from this run.
  MessageHeader message_header(Index count, bool with_history) const;
  HalfKick<Real> half_kick(ParticleStore& s, const IntegrationParams& p) {
    return HalfKick<Real>{s.velocity.data(), s.angular_velocity.data(), forces_.force.data(),
                          kTorque ? forces_.torque.data() : nullptr, s.mass.data(), s.inertia.data(), 0.5 * p.dt,
                          p.gravity, p.fp32_state};
  }
  SlotTable<Real, kKept> slot_table() {
    SlotTable<Real, kKept> t;
    t.partner = history_.partner.data();
#define GS_POINT_AT_FIELD(name, value, bit) t.name = history_.name.data();
    GS_HISTORY_FIELDS(GS_POINT_AT_FIELD)
#undef GS_POINT_AT_FIELD
    t.slots = history_.slots;
    t.strides = history_.strides;
    return t;
  }
  void grow_history(std::size_t capacity);
  void keep_in_order(ParticleStore& s, const Index* order, Index n);
  static std::vector<Vec3<Real>> narrowed(const std::vector<Vec3d>& v, Index n) {
    if (v.size() != std::size_t(n)) throw std::invalid_argument("one force per owned particle expected");
    std::vector<Vec3<Real>> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = Vec3<Real>(v[i]);
    return out;
  }
  static std::vector<Vec3d> widen(const DeviceArray<Vec3<Real>>& a, Index n) {
    std::vector<Vec3<Real>> h = a.to_host();
    std::vector<Vec3d> out(n);
    for (Index i = 0; i < n; ++i) out[i] = Vec3d(h[i]);
    return out;
  }

  DeviceArray<PairParams<Real, Model>> pairs_;
  int n_materials_ = 0;
  DeviceArray<Wall> walls_;
  DeviceArray<WallScreen> wall_screens_;  // per wall, at the pose walls_ holds
  int n_walls_ = 0;
  DeviceMeshes meshes_;
  DeviceArray<Fault> fault_;
  CellList cells_;
  VerletList verlet_{Exec::backend};  // empty where Exec::verlet_list is false
  ForceArrays<Real> forces_;
  ContactHistory<Real> history_;
  // Reused staging for data movement (reorder, migration, ghosts).
  mutable DeviceArray<unsigned char> staging_{Exec::backend};
};

}  // namespace gs

#include "engine/step_kernels_impl_detail.hpp"
#include "engine/step_kernels_transfer.hpp"
