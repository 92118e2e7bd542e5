#pragma once
// RankExchange over a Transport and a Decomposition: migration of particles
// (with contact history) to their owners, ghost copies for the neighbours,
// re-balancing, and agreement on faults. Particles are packed and unpacked by
// the backend's kernels (ParticleMovement::pack / unpack), and who goes where is
// decided by the backend's ParticleRouter; the host only moves the messages.
#include <chrono>
#include <memory>

#include "comm/device_link.hpp"
#include "comm/host_message_buffer.hpp"
#include "comm/transport.hpp"
#include "decomposition/decomposition.hpp"
#include "engine/particle_router.hpp"
#include "engine/rank_exchange.hpp"
#include "decomposition/owned_bounds.hpp"
#include "scene/scene.hpp"

namespace gs {

class DomainExchange final : public RankExchange {
 public:
  // halo: interaction range (the largest particle diameter), to which
  // set_skin adds the skin; box: the
  // domain's periodic axes, across whose faces halos reach.
  DomainExchange(Transport& transport, std::unique_ptr<Decomposition> decomposition, double halo,
                 const DecompositionSpec& spec, const PeriodicBox& box = {});

  int rank() const override { return transport_.rank(); }
  int ranks() const override { return transport_.size(); }
  bool owns(const Vec3d& x) const override { return decomposition_->owner(x) == rank(); }
  void owned_bounds(Vec3d& lo, Vec3d& hi) const override { gs::owned_bounds(*decomposition_, rank(), lo, hi); }
  void migrate(ParticleStore& s, ParticleMovement& k) override;
  void refresh_ghosts(ParticleStore& s, ParticleMovement& k) override;
  double set_skin(double skin) override;
  bool halo_stale(const ParticleStore& s, ParticleMovement& k, bool due) override;
  void start_forward(ParticleStore& s, ParticleMovement& k) override;
  void finish_forward(ParticleStore& s, ParticleMovement& k) override;
  bool rebalance(ParticleStore& s, ParticleMovement& k) override;
  std::string first_fault(const std::string& local) override;
  long long total(long long local) override;
  void sum(std::vector<double>& values) override { transport_.sum(values); }
  std::string describe() const override {
    return decomposition_->describe() + (link_ ? "; particles move over NCCL" : "; particles move through host buffers");
  }
  void time_phases(bool on) override { timed_ = on; }
  ExchangeSplit split() const override { return split_; }

  const Decomposition& decomposition() const { return *decomposition_; }
  // Moves message payloads over `link` (GPU ranks) instead of through the host.
  void use_device_link(std::unique_ptr<DeviceLink> link) { link_ = std::move(link); }
  bool has_device_link() const { return link_ != nullptr; }

 private:
  void send_to_owners(ParticleStore& s, ParticleMovement& k, const std::vector<int>& peers);
  // The router, on the store's backend, with the current map and these peers.
  ParticleRouter& router(const ParticleStore& s, const std::vector<int>& peers);
  std::vector<MessageHeader> trade(ParticleMovement& k, const ParticleStore& s, const std::vector<int>& peers,
                                   bool with_history);
  void unpack(ParticleMovement& k, ParticleStore& s, const std::vector<MessageHeader>& headers, bool as_ghosts);
  // On timed calls: waits for the device and charges the time since the
  // previous lap to `phase`.
  void lap(ParticleMovement& k, double ExchangeSplit::*phase);
  std::vector<int> all_other_ranks() const;
  // The ranks this one trades ghosts with: the decomposition's neighbours,
  // and across the periodic faces those on the other side.
  std::vector<int> neighbours() const;
  double reach() const { return halo_ + skin_; }  // how far ghosts reach
  OwnerMapHost owner_map() const;  // the decomposition's, with the periodic box

  Transport& transport_;
  std::unique_ptr<Decomposition> decomposition_;
  double halo_;
  double skin_ = 0;
  DecompositionSpec spec_;
  PeriodicBox box_;
  std::vector<int> peers_;  // neighbours of this rank, ascending
  bool timed_ = false;
  ExchangeSplit split_;
  std::chrono::steady_clock::time_point last_lap_;
  std::unique_ptr<ParticleRouter> router_;
  Backend router_backend_ = Backend::cpu;
  bool map_current_ = false;     // the router holds decomposition_'s current map
  DeviceArray<Index> list_;      // store indices the router selected (staying particles)
  // The halo's plan, from the last refresh_ghosts (LAMMPS's borders(), Cabana's
  // Halo): per peer the owned particles sent as ghosts (store indices), and
  // where that peer's ghosts lie here. Valid while the store's revision is
  // plan_revision_.
  std::vector<DeviceArray<Index>> send_list_;
  std::vector<Index> ghost_first_, ghost_count_;
  std::uint64_t plan_revision_ = 0;
  bool plan_valid_ = false;
  std::vector<DeviceArray<unsigned char>> outbox_, inbox_;  // one message per peer
  // The forward's messages on the host (not over the device link), per peer,
  // kept from step to step; in flight while forward_started_.
  std::vector<HostMessageBuffer> host_out_, host_in_;
  bool forward_started_ = false;
  std::unique_ptr<DeviceLink> link_;
  std::size_t sent_ = 0;         // particles trade() sent
};

}  // namespace gs
