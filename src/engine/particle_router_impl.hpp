#pragma once
// ParticleRouter over an execution policy (CpuExec or CudaExec).
#include <stdexcept>
#include <string>

#include "backend/memory.hpp"
#include "engine/particle_router.hpp"

namespace gs {

using RouteTag = std::uint64_t;  // bit p: peer slot p; bit kNoPeer: not a peer
constexpr RouteTag route_bit(int slot) { return RouteTag(1) << slot; }

// The tag bit for rank r as seen from `self` (0 for self itself).
struct PeerBits {
  const int* slot_of_rank;  // -1 for ranks that are not peers
  int self;
  GS_HD RouteTag of(int r) const {
    if (r == self) return 0;
    const int slot = slot_of_rank[r];
    return route_bit(slot < 0 ? ParticleRouter::kNoPeer : slot);
  }
};

struct TagOwner {
  const Vec3d* x;
  OwnerMap map;
  PeerBits peers;
  RouteTag* tag;
  GS_HD void operator()(Index i) const { tag[i] = peers.of(map.owner_of(x[i])); }
};

struct TagGhost {
  const Vec3d* x;
  OwnerMap map;
  PeerBits peers;
  double halo;
  RouteTag* tag;

  struct Collect {
    const PeerBits& peers;
    RouteTag& t;
    GS_HD void operator()(int r) const { t |= peers.of(r); }
  };
  GS_HD void operator()(Index i) const {
    RouteTag t = 0;
    map.for_each_owner_near(x[i], halo, Collect{peers, t});
    tag[i] = t;
  }
};

struct TaggedFor {
  const RouteTag* tag;
  RouteTag bits;  // 0: tagged for none
  GS_HD bool operator()(const Index& i) const { return bits == 0 ? tag[i] == 0 : (tag[i] & bits) != 0; }
};

template <class Exec>
class ParticleRouterImpl final : public ParticleRouter {
 public:
  ParticleRouterImpl()
      : owner_(Exec::backend), slot_of_rank_(Exec::backend), tag_(Exec::backend), scratch_(Exec::backend) {}

  void set_map(const OwnerMapHost& map) override {
    shape_ = map.shape;
    owner_.from_host(map.owner);
  }

  void set_peers(int self, int ranks, const std::vector<int>& peers) override {
    if (self == self_ && ranks == ranks_ && peers == peers_) return;  // the common case: nothing to upload
    if (int(peers.size()) > kMaxPeers)
      throw std::runtime_error("a rank has " + std::to_string(peers.size()) + " neighbours; at most " +
                               std::to_string(kMaxPeers) + " are supported");
    std::vector<int> slot(std::size_t(ranks), -1);
    for (std::size_t p = 0; p < peers.size(); ++p) slot.at(std::size_t(peers[p])) = int(p);
    slot_of_rank_.from_host(slot);
    self_ = self;
    ranks_ = ranks;
    peers_ = peers;
  }

  void tag_owners(const ParticleStore& s) override {
    tag_.resize(std::size_t(s.n_owned));
    Exec::parallel_for(s.n_owned, TagOwner{s.position.data(), map(), peer_bits(), tag_.data()});
  }

  void tag_ghosts(const ParticleStore& s, double halo) override {
    tag_.resize(std::size_t(s.n_owned));
    Exec::parallel_for(s.n_owned, TagGhost{s.position.data(), map(), peer_bits(), halo, tag_.data()});
  }

  void select(int slot, DeviceArray<Index>& out) override {
    const Index n = Index(tag_.size());
    out.resize(std::size_t(n));
    const RouteTag bits = slot == kStay ? 0 : route_bit(slot);
    out.resize(std::size_t(Exec::select(n, TaggedFor{tag_.data(), bits}, out.data(), scratch_)));
  }

 private:
  OwnerMap map() const { return {shape_, owner_.data()}; }
  PeerBits peer_bits() const { return {slot_of_rank_.data(), self_}; }

  OwnerMapShape shape_;
  DeviceArray<int> owner_, slot_of_rank_;
  DeviceArray<RouteTag> tag_;
  DeviceArray<unsigned char> scratch_;
  int self_ = -1, ranks_ = 0;
  std::vector<int> peers_;
};

}  // namespace gs
