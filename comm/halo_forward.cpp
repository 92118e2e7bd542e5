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
  const bool mine = due || !plan_valid_ || s.revision != plan_revision_;
  const bool any = transport_.min(mine ? 0 : 1) == 0;
  lap(k, &ExchangeSplit::route);
  return any;
}

// Packed on the backend straight from the send lists into the send
// buffers; through host buffers kept from step to step (CPU ranks, GPU ranks
// sharing a GPU) or over the device link. Both sides know every message's
// size from the rebuild, so no header travels. Through the host the
// messages travel between start_forward and finish_forward, while the caller
// computes the forces that need no ghost; over the device link they have
// arrived when start_forward returns.
void DomainExchange::start_forward(ParticleStore& s, ParticleMovement& k) {
  if (!plan_valid_ || s.revision != plan_revision_)
    throw std::logic_error("ghosts forwarded over a halo that no longer describes the store");
  if (forward_started_) throw std::logic_error("a forward of the ghosts started before the last one finished");
  last_lap_ = std::chrono::steady_clock::now();
  const std::size_t n = peers_.size();
  const bool host_is_backend = router_backend_ == Backend::cpu;
  std::vector<const unsigned char*> send(n);
  std::vector<unsigned char*> recv(n);
  std::vector<std::size_t> send_bytes(n), recv_bytes(n);
  host_out_.resize(n);
  host_in_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    send_bytes[p] = forward_bytes(send_list_[p].size(), s.fields_kept);
    recv_bytes[p] = forward_bytes(std::size_t(ghost_count_[p]), s.fields_kept);
    if (!link_) recv[p] = host_in_[p].hold(router_backend_, recv_bytes[p]);
    if (send_bytes[p] == 0) continue;
    if (host_is_backend && !link_) {
      unsigned char* out = host_out_[p].hold(router_backend_, send_bytes[p]);
      k.pack_forward(s, send_list_[p], out);
      send[p] = out;
      continue;
    }
    outbox_[p].resize(send_bytes[p]);
    k.pack_forward(s, send_list_[p], outbox_[p].data());
    send[p] = outbox_[p].data();
    if (link_) continue;
    unsigned char* out = host_out_[p].hold(router_backend_, send_bytes[p]);
    backend_copy_to_host(router_backend_, out, outbox_[p].data(), send_bytes[p]);
    send[p] = out;
  }
  lap(k, &ExchangeSplit::pack);
  if (link_) {
    for (std::size_t p = 0; p < n; ++p) {
      inbox_[p].resize(recv_bytes[p]);
      recv[p] = inbox_[p].data();
    }
    link_->exchange(peers_, send, send_bytes, recv, recv_bytes);
  } else {
    transport_.start_exchange(peers_, send, send_bytes, recv, recv_bytes);
  }
  forward_started_ = true;
  lap(k, &ExchangeSplit::transfer);
}

void DomainExchange::finish_forward(ParticleStore& s, ParticleMovement& k) {
  if (!forward_started_) throw std::logic_error("a forward of the ghosts finished that had not started");
  forward_started_ = false;
  last_lap_ = std::chrono::steady_clock::now();
  if (!link_) transport_.finish_exchange();
  lap(k, &ExchangeSplit::transfer);
  const bool host_is_backend = router_backend_ == Backend::cpu;
  for (std::size_t p = 0; p < peers_.size(); ++p) {
    const std::size_t bytes = forward_bytes(std::size_t(ghost_count_[p]), s.fields_kept);
    if (bytes == 0) continue;
    const unsigned char* payload = inbox_[p].data();
    if (!link_) {
      payload = host_in_[p].data();
      if (!host_is_backend) {
        inbox_[p].resize(bytes);
        backend_copy_from_host(router_backend_, inbox_[p].data(), payload, bytes);
        payload = inbox_[p].data();
      }
    }
    k.unpack_forward(s, payload, ghost_first_[p], ghost_count_[p]);
  }
  lap(k, &ExchangeSplit::unpack);
  ++split_.forwards;
}

}  // namespace gs
