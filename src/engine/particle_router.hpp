#pragma once
// Where a rank's owned particles must go, decided by backend kernels from
// their positions, so that no position goes to the host: to their owner
// (migration), or as ghost copies to the ranks within interaction range.
// Data movement only; comm/ moves what this selects.
#include <cstdint>
#include <memory>
#include <vector>

#include "backend/device_array.hpp"
#include "core/owner_map.hpp"
#include "engine/particle_store.hpp"

namespace gs {

class ParticleRouter {
 public:
  static constexpr int kMaxPeers = 63;  // one tag bit per peer, one for "no peer"
  static constexpr int kStay = -1;      // select(): particles tagged for no peer
  static constexpr int kNoPeer = 63;    // select(): particles whose destination is no peer

  virtual ~ParticleRouter() = default;

  virtual void set_map(const OwnerMapHost& map) = 0;
  // This rank and its peers (ascending, at most kMaxPeers): peer slot p is peers[p].
  virtual void set_peers(int self, int ranks, const std::vector<int>& peers) = 0;

  // Tags each owned particle with the peer slot of its owner (none when it
  // is this rank; kNoPeer when its owner is not a peer: it moved too far).
  virtual void tag_owners(const ParticleStore& s) = 0;
  // Tags each owned particle with the peer slots whose region is within box
  // distance `halo` of it (Decomposition::ranks_near).
  virtual void tag_ghosts(const ParticleStore& s, double halo) = 0;
  // Store indices, ascending, of the owned particles tagged for `slot` (or
  // tagged for none: kStay); `out` is resized to their count.
  virtual void select(int slot, DeviceArray<Index>& out) = 0;
};

std::unique_ptr<ParticleRouter> make_particle_router(Backend backend);
std::unique_ptr<ParticleRouter> make_particle_router_cpu();
std::unique_ptr<ParticleRouter> make_particle_router_cuda();

}  // namespace gs
