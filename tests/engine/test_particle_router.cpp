// The device-side router against the host decomposition it flattens: for
// every rank of a slab and of a METIS partition, each owned particle is
// tagged for exactly the peers that Decomposition::owner() and ranks_near()
// name, on every backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "decomposition/metis_decomposition.hpp"
#include "decomposition/slab_decomposition.hpp"
#include "engine/particle_router.hpp"
#include "support/support.hpp"
#include "../decomposition/decomposition_test_helpers.hpp"

namespace gs {
namespace {

ParticleStore store_at(Backend b, const std::vector<Vec3d>& x) {
  ParticleStore s;
  s.backend = b;
  s.position = DeviceArray<Vec3d>(b);
  s.position.from_host(x);
  s.n_owned = Index(x.size());
  return s;
}

std::vector<Index> selected(ParticleRouter& r, int slot, Backend b) {
  DeviceArray<Index> out(b);
  r.select(slot, out);
  return out.to_host();
}

// Store indices whose reference slots contain `slot`.
std::vector<Index> expected(const std::vector<std::vector<int>>& slots, int slot) {
  std::vector<Index> out;
  for (std::size_t i = 0; i < slots.size(); ++i)
    if (std::find(slots[i].begin(), slots[i].end(), slot) != slots[i].end()) out.push_back(Index(i));
  return out;
}

int slot_of(const std::vector<int>& peers, int r) {
  const auto it = std::find(peers.begin(), peers.end(), r);
  return it == peers.end() ? ParticleRouter::kNoPeer : int(it - peers.begin());
}

// Query points: random in and around the domain, and on cell faces, where
// rounding decides the owner.
std::vector<Vec3d> queries(const CoarseGrid& g) {
  std::vector<Vec3d> q = test::query_points(g, 3000, 41);
  const Vec3d lo(g.lo[0], g.lo[1], g.lo[2]), hi(g.hi[0], g.hi[1], g.hi[2]);
  const Vec3d pad = (hi - lo) * 0.1;
  const auto around = test::uniform_points(500, lo - pad, hi + pad, 42);
  q.insert(q.end(), around.begin(), around.end());
  return q;
}

void check_router(Backend b, const Decomposition& d, double halo) {
  const std::vector<Vec3d> x = queries(d.grid());
  const ParticleStore s = store_at(b, x);
  std::unique_ptr<ParticleRouter> router = make_particle_router(b);
  router->set_map(d.owner_map());
  for (int self = 0; self < d.n_ranks(); ++self) {
    const std::vector<int> peers = d.neighbours(self);
    router->set_peers(self, d.n_ranks(), peers);
    std::vector<std::vector<int>> owner_slot(x.size()), ghost_slots(x.size());
    std::vector<int> near;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const int o = d.owner(x[i]);
      owner_slot[i] = {o == self ? ParticleRouter::kStay : slot_of(peers, o)};
      near.clear();
      d.ranks_near(x[i], halo, self, near);
      for (int r : near) ghost_slots[i].push_back(slot_of(peers, r));
    }
    router->tag_owners(s);
    for (int slot = ParticleRouter::kStay; slot < int(peers.size()); ++slot)
      EXPECT_EQ(selected(*router, slot, b), expected(owner_slot, slot)) << "owners, rank " << self << " slot " << slot;
    EXPECT_EQ(selected(*router, ParticleRouter::kNoPeer, b), expected(owner_slot, ParticleRouter::kNoPeer));
    router->tag_ghosts(s, halo);
    for (int slot = 0; slot < int(peers.size()); ++slot)
      EXPECT_EQ(selected(*router, slot, b), expected(ghost_slots, slot)) << "ghosts, rank " << self << " slot " << slot;
    EXPECT_EQ(selected(*router, ParticleRouter::kNoPeer, b), expected(ghost_slots, ParticleRouter::kNoPeer));
  }
}

class RouterTest : public testing::TestWithParam<Backend> {};

TEST_P(RouterTest, SlabsMatchTheDecomposition) {
  const Vec3d lo(0, 0, 0), hi(1, 0.5, 2);
  const auto pts = test::uniform_points(20000, lo, hi + Vec3d(0, 0, -1.2), 31);  // denser low: uneven slabs
  const auto d = SlabDecomposition::from_positions(lo, hi, 0.07, 4, 2, pts);
  for (double h : {0.0, 0.035, 0.07}) check_router(GetParam(), d, h);
}

TEST_P(RouterTest, MetisMatchesTheDecomposition) {
  const Vec3d lo(-1, -1, 0), hi(1, 1, 0.4);
  const auto pts = test::annulus_points(20000, 0.3, 0.9, 0.4, 32);
  const auto d = MetisDecomposition::from_positions(lo, hi, 0.1, 5, pts);
  for (double h : {0.0, 0.05, 0.1}) check_router(GetParam(), d, h);
}

TEST_P(RouterTest, RefusesMorePeersThanTagBits) {
  std::unique_ptr<ParticleRouter> router = make_particle_router(GetParam());
  std::vector<int> peers(ParticleRouter::kMaxPeers + 1);
  for (std::size_t p = 0; p < peers.size(); ++p) peers[p] = int(p) + 1;
  EXPECT_THROW(router->set_peers(0, int(peers.size()) + 1, peers), std::runtime_error);
}

INSTANTIATE_TEST_SUITE_P(Backends, RouterTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
