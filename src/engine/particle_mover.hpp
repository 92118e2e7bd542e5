#pragma once
// ParticleMovement over an execution policy `Exec` (CpuExec or CudaExec) and
// force precision `Real`: gathers, scatters and copies run as backend kernels
// and copy values bit for bit. Which history fields move is the run's
// (StepState::kept), read at run time: one instantiation serves every
// contact model and set of effects.
#include <stdexcept>
#include <string>

#include "engine/gather.hpp"
#include "engine/pair_carry.hpp"
#include "engine/output_chunk.hpp"
#include "engine/owned_id_order.hpp"
#include "engine/particle_movement.hpp"
#include "engine/step_state.hpp"
#include "engine/surface_rows.hpp"

namespace gs {

// Whether particle i has a stored contact on an analytic wall.
struct TouchesWall {
  const Index* row;
  const ParticleId* partner;
  HistoryStrides strides;
  int slots;
  GS_HD bool operator()(Index i) const {
    const Index r = row[i];
    if (r == kNoSurfaceRow) return false;
    for (int k = 0; k < slots; ++k) {
      const ParticleId p = partner[strides.at(k, std::size_t(r))];
      if (p >= kWallPartnerBase && p != kNoPartner) return true;
    }
    return false;
  }
};

template <class Exec, class Real>
class ParticleMover final : public ParticleMovement {
 public:
  ParticleMover(StepState<Real>& state, PairCarry<Exec, Real>& pairs) : st_(state), pairs_(pairs) {}

  void reserve(Index n) override {
    st_.forces.force.resize(n);
    if (st_.torque) st_.forces.torque.resize(n);
    // The particles beyond those the history knows have no surface row
    // (until arrive gives them theirs, or the next build: engine/surface_rows.hpp).
    ContactHistory<Real>& h = st_.history;
    if (st_.keeps_history() && std::size_t(n) > h.row.size()) {
      const std::size_t had = h.row.size();
      h.row.resize(std::size_t(n));
      Exec::parallel_for(Index(std::size_t(n) - had), Fill<Index>{h.row.data() + had, kNoSurfaceRow});
    }
  }

  void release_forces() override {
    st_.forces.force.discard();
    st_.forces.torque.discard();
  }

  MessageHeader pack(const ParticleStore& s, const DeviceArray<Index>& which, bool with_history,
                     DeviceArray<unsigned char>& out) const override;
  void unpack(ParticleStore& s, const MessageHeader& h, const unsigned char* payload, bool as_ghosts) override;
  void pack_forward(const ParticleStore& s, const DeviceArray<Index>& which, unsigned char* out) const override;
  void unpack_forward(ParticleStore& s, const unsigned char* payload, Index first, Index count) override;
  void keep_owned(ParticleStore& s, const DeviceArray<Index>& keep) override;
  void reorder(ParticleStore& s, const DeviceArray<Index>& order) override;
  void append(ParticleStore& s, const ParticleRecords& r, bool as_ghosts) override;
  void set_forces(const ParticleStore& s, const std::vector<Vec3d>& force, const std::vector<Vec3d>& torque) override {
    st_.forces.force.from_host(narrowed(force, s.n_owned));
    if (st_.torque) st_.forces.torque.from_host(narrowed(torque, s.n_owned));
    reserve(s.size());
  }
  void set_history(const ParticleStore& s, const HostHistory& h) override;

  std::vector<Vec3d> forces(const ParticleStore& s) const override { return widened(st_.forces.force, s.n_owned); }
  std::vector<Vec3d> torques(const ParticleStore& s) const override {
    if (!st_.torque) return std::vector<Vec3d>(s.n_owned);
    return widened(st_.forces.torque, s.n_owned);
  }
  void owned_to_host(const ParticleStore& s, const RowOrder& order, ParticleSnapshot& into, HostPins& pins,
                     bool with_forces) const override;
  void history_to_host(const ParticleStore& s, const RowOrder& order, HostHistory& into, HostPins& pins) const override;
  void wall_contact_history(const ParticleStore& s, ParticleRecords& into, HostPins& pins) const override;
  RowOrder owned_row_order(const ParticleStore& s, DeviceArray<Index>& storage) const override {
    return gs::owned_row_order<Exec>(s.id.data(), s.n_owned, storage, st_.staging);
  }

  void synchronize() const override { Exec::synchronize(); }
  std::size_t bytes() const override {
    std::size_t history = st_.history.row.bytes() + st_.history.partner.bytes() + st_.pairs.bytes();
    for_each_history_field(st_.history, [&](const char*, unsigned, const auto& a) { history += a.bytes(); });
    return st_.forces.force.bytes() + st_.forces.torque.bytes() + history + st_.staging.bytes();
  }

 private:
  // What a message of `count` particles of store s carries from this run.
  MessageHeader message_header(const ParticleStore& s, Index count, bool with_history) const;
  void keep_in_order(ParticleStore& s, const Index* order, Index n);
  void arrive_from_host(const ParticleStore& s, Index first, const HostHistory& h);
  static std::vector<Vec3<Real>> narrowed(const std::vector<Vec3d>& v, Index n) {
    if (v.size() != std::size_t(n)) throw std::invalid_argument("one force per owned particle expected");
    std::vector<Vec3<Real>> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = Vec3<Real>(v[i]);
    return out;
  }
  static std::vector<Vec3d> widened(const DeviceArray<Vec3<Real>>& a, Index n) {
    std::vector<Vec3<Real>> h = a.to_host();
    std::vector<Vec3d> out(n);
    for (Index i = 0; i < n; ++i) out[i] = Vec3d(h[i]);
    return out;
  }

  StepState<Real>& st_;
  PairCarry<Exec, Real>& pairs_;
};

}  // namespace gs

#include "engine/particle_mover_history.hpp"
#include "engine/particle_mover_transfer.hpp"
#include "engine/particle_mover_forward.hpp"
#include "engine/particle_mover_output.hpp"
