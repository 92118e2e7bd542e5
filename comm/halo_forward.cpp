// The halo between its rebuilds (LAMMPS's forward_comm, Cabana's Halo::gather):
// DomainExchange's skin, the collective decision to rebuild, and the forward
// of the ghosts' changing fields over the send lists refresh_ghosts recorded.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "backend/memory.hpp"
#include "comm/domain_exchange.hpp"
#include "engine/ghost_forward.hpp"

namespace gs {

// Decomposition::neighbours holds every rank owning a coarse cell next to one
// of this rank's: every rank within one cell edge. Ghosts may reach no
// farther, so the skin is cut to the narrowest edge of an axis of several
// cells (an axis of one cell has no neighbour along it). Every rank computes
// the same value from the same grid.
double DomainExchange::set_skin(double skin) {
  const CoarseGrid& g = decomposition_->grid();
  double edge = -1;
  for (int a = 0; a < 3; ++a)
    if (g.dims[std::size_t(a)] > 1) edge = edge < 0 ? g.edge[std::size_t(a)] : std::min(edge, g.edge[std::size_t(a)]);
  skin_ = std::max(0.0, edge < 0 ? skin : std::min(skin, edge - halo_));
  peers_ = neighbours();  // across periodic faces they depend on the reach
  plan_valid_ = false;
  return skin_;
}

bool DomainExchange::halo_stale(const ParticleStore& s, ParticleMovement& k, bool due) {
  last_lap_ = std::chrono::steady_clock::now();
  // Without a skin every step rebuilds, on every rank alike: no vote needed.
  if (!(skin_ > 0)) return true;
  const bool mine = due || !plan_valid_ || s.revision != plan_revision_ || router(s, peers_).moved_beyond(s, 0.5 * skin_);
  const bool any = transport_.min(mine ? 0 : 1) == 0;
  lap(k, &ExchangeSplit::route);
  return any;
}

// Packed on the backend straight from the send lists; through host buffers
// (CPU ranks, GPU ranks sharing a GPU) or over the device link. Both sides
// know every message's size from the rebuild, so no header travels.
void DomainExchange::forward_ghosts(ParticleStore& s, ParticleMovement& k) {
  if (!plan_valid_ || s.revision != plan_revision_)
    throw std::logic_error("ghosts forwarded over a halo that no longer describes the store");
  last_lap_ = std::chrono::steady_clock::now();
  const std::size_t n = peers_.size();
  const bool host_is_backend = router_backend_ == Backend::cpu;
  std::vector<Bytes> send(n), recv;
  std::vector<std::size_t> send_bytes(n), recv_bytes(n);
  for (std::size_t p = 0; p < n; ++p) {
    send_bytes[p] = forward_bytes(send_list_[p].size());
    recv_bytes[p] = forward_bytes(std::size_t(ghost_count_[p]));
    if (send_bytes[p] == 0) continue;
    if (host_is_backend && !link_) {
      send[p].resize(send_bytes[p]);
      k.pack_forward(s, send_list_[p], reinterpret_cast<unsigned char*>(send[p].data()));
      continue;
    }
    outbox_[p].resize(send_bytes[p]);
    k.pack_forward(s, send_list_[p], outbox_[p].data());
    if (link_) continue;
    send[p].resize(send_bytes[p]);
    backend_copy_to_host(router_backend_, send[p].data(), outbox_[p].data(), send_bytes[p]);
  }
  lap(k, &ExchangeSplit::pack);
  if (link_) {
    std::vector<const unsigned char*> from(n);
    std::vector<unsigned char*> to(n);
    for (std::size_t p = 0; p < n; ++p) {
      inbox_[p].resize(recv_bytes[p]);
      from[p] = outbox_[p].data();
      to[p] = inbox_[p].data();
    }
    link_->exchange(peers_, from, send_bytes, to, recv_bytes);
  } else {
    transport_.exchange(peers_, send, recv);
  }
  lap(k, &ExchangeSplit::transfer);
  for (std::size_t p = 0; p < n; ++p) {
    if (recv_bytes[p] == 0) continue;
    const unsigned char* payload = inbox_[p].data();
    if (!link_) {
      if (recv[p].size() != recv_bytes[p])
        throw std::runtime_error("a ghost update from rank " + std::to_string(peers_[p]) + " has " +
                                 std::to_string(recv[p].size()) + " bytes, " + std::to_string(recv_bytes[p]) +
                                 " expected");
      payload = reinterpret_cast<const unsigned char*>(recv[p].data());
      if (!host_is_backend) {
        inbox_[p].resize(recv_bytes[p]);
        backend_copy_from_host(router_backend_, inbox_[p].data(), recv[p].data(), recv_bytes[p]);
        payload = inbox_[p].data();
      }
    }
    k.unpack_forward(s, payload, ghost_first_[p], ghost_count_[p]);
  }
  lap(k, &ExchangeSplit::unpack);
  ++split_.forwards;
}

}  // namespace gs
