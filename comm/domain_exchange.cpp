#include "comm/domain_exchange.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstring>
#include <stdexcept>

#include "backend/memory.hpp"
#include "decomposition/halo_neighbours.hpp"
#include "decomposition/metis_decomposition.hpp"
#include "decomposition/slab_decomposition.hpp"

namespace gs {
namespace {

// The header of a message from rank `from`, checked before anything is
// sized from it.
MessageHeader read_header(const Bytes& b, int from) {
  MessageHeader h;
  const std::string bad = "a particle message from rank " + std::to_string(from) + " is corrupt";
  if (b.size() < sizeof(h)) throw std::runtime_error(bad);
  std::memcpy(&h, b.data(), sizeof(h));
  const bool reals_ok = h.real_bytes == 0 || h.real_bytes == int(sizeof(float)) || h.real_bytes == int(sizeof(double));
  if (h.check != kMessageCheck || h.slots < 0 || h.slots > kMaxContactSlots || !reals_ok || h.count == 0 ||
      h.count > std::uint64_t(INT32_MAX))
    throw std::runtime_error(bad);
  return h;
}

std::vector<Vec3d> owned_positions(const ParticleStore& s) {
  std::vector<Vec3d> x = s.position.to_host();
  x.resize(std::size_t(s.n_owned));
  return x;
}

}  // namespace

DomainExchange::DomainExchange(Transport& transport, std::unique_ptr<Decomposition> decomposition, double halo,
                               const DecompositionSpec& spec, const PeriodicBox& box)
    : transport_(transport), decomposition_(std::move(decomposition)), halo_(halo), spec_(spec), box_(box) {
  if (decomposition_->n_ranks() != transport_.size())
    throw std::logic_error("decomposition and transport disagree on the number of ranks");
  peers_ = neighbours();
}

OwnerMapHost DomainExchange::owner_map() const {
  OwnerMapHost m = decomposition_->owner_map();
  m.shape.box = box_;
  return m;
}

std::vector<int> DomainExchange::neighbours() const {
  std::vector<int> peers = decomposition_->neighbours(rank());
  if (box_.axes == 0) return peers;
  const std::vector<std::vector<int>> near = halo_neighbours(owner_map(), reach(), ranks());
  const std::vector<int>& mine = near[std::size_t(rank())];
  peers.insert(peers.end(), mine.begin(), mine.end());
  std::sort(peers.begin(), peers.end());
  peers.erase(std::unique(peers.begin(), peers.end()), peers.end());
  return peers;
}

std::vector<int> DomainExchange::all_other_ranks() const {
  std::vector<int> r;
  for (int k = 0; k < ranks(); ++k)
    if (k != rank()) r.push_back(k);
  return r;
}

void DomainExchange::lap(ParticleMovement& k, double ExchangeSplit::*phase) {
  if (!timed_) return;
  k.synchronize();
  const auto now = std::chrono::steady_clock::now();
  split_.*phase += std::chrono::duration<double>(now - last_lap_).count();
  last_lap_ = now;
}

ParticleRouter& DomainExchange::router(const ParticleStore& s, const std::vector<int>& peers) {
  if (!router_ || router_backend_ != s.position.backend()) {
    router_ = make_particle_router(s.position.backend());
    router_backend_ = s.position.backend();
    list_ = DeviceArray<Index>(router_backend_);
    send_list_.clear();
    plan_valid_ = false;
    outbox_.clear();
    inbox_.clear();
    map_current_ = false;
  }
  if (!map_current_) router_->set_map(owner_map());
  map_current_ = true;
  router_->set_peers(rank(), ranks(), peers);
  return *router_;
}

// Packs the particles the router tagged for each peer into one message per
// peer and swaps messages with every peer: the headers over the transport,
// the payloads over the device link when there is one (they never leave
// backend memory), else through the host with their headers. Leaves what
// arrived from peers[p] in inbox_[p]; returns the headers (count 0: none).
std::vector<MessageHeader> DomainExchange::trade(ParticleMovement& k, const ParticleStore& s,
                                                 const std::vector<int>& peers, bool with_history) {
  const std::size_t n = peers.size();
  while (outbox_.size() < n) {
    outbox_.emplace_back(router_backend_);
    inbox_.emplace_back(router_backend_);
    send_list_.emplace_back(router_backend_);
  }
  std::vector<Bytes> send(n), recv;
  for (std::size_t p = 0; p < n; ++p) {
    DeviceArray<Index>& list = send_list_[p];
    router_->select(int(p), list);
    sent_ += list.size();
    lap(k, &ExchangeSplit::route);
    if (list.size() == 0) continue;
    const MessageHeader h = k.pack(s, list, with_history, outbox_[p]);
    const std::size_t payload = link_ ? 0 : outbox_[p].size();
    send[p].resize(sizeof(h) + payload);
    std::memcpy(send[p].data(), &h, sizeof(h));
    if (payload > 0) backend_copy_to_host(router_backend_, send[p].data() + sizeof(h), outbox_[p].data(), payload);
    lap(k, &ExchangeSplit::pack);
  }
  transport_.exchange(peers, send, recv);

  std::vector<MessageHeader> headers(n);
  std::vector<std::size_t> send_bytes(n, 0), recv_bytes(n, 0);
  for (std::size_t p = 0; p < n; ++p) {
    if (!send[p].empty()) send_bytes[p] = outbox_[p].size();
    if (recv[p].empty()) continue;
    headers[p] = read_header(recv[p], peers[p]);
    recv_bytes[p] = MessageLayout(headers[p]).bytes;
    inbox_[p].resize(recv_bytes[p]);
    if (link_) continue;
    if (recv[p].size() != sizeof(MessageHeader) + recv_bytes[p])
      throw std::runtime_error("a particle message from rank " + std::to_string(peers[p]) + " is truncated");
    backend_copy_from_host(router_backend_, inbox_[p].data(), recv[p].data() + sizeof(MessageHeader), recv_bytes[p]);
  }
  if (link_) {
    std::vector<const unsigned char*> from(n);
    std::vector<unsigned char*> to(n);
    for (std::size_t p = 0; p < n; ++p) {
      from[p] = outbox_[p].data();
      to[p] = inbox_[p].data();
    }
    link_->exchange(peers, from, send_bytes, to, recv_bytes);
  }
  lap(k, &ExchangeSplit::transfer);
  return headers;
}

// Appends the particles that arrived, in peer order.
void DomainExchange::unpack(ParticleMovement& k, ParticleStore& s, const std::vector<MessageHeader>& headers,
                            bool as_ghosts) {
  for (std::size_t p = 0; p < headers.size(); ++p)
    if (headers[p].count > 0) k.unpack(s, headers[p], inbox_[p].data(), as_ghosts);
  lap(k, &ExchangeSplit::unpack);
}

void DomainExchange::send_to_owners(ParticleStore& s, ParticleMovement& k, const std::vector<int>& peers) {
  plan_valid_ = false;
  s.drop_ghosts();
  last_lap_ = std::chrono::steady_clock::now();
  router(s, peers).tag_owners(s);
  sent_ = 0;
  const std::vector<MessageHeader> arrived = trade(k, s, peers, true);
  router_->select(ParticleRouter::kStay, list_);
  lap(k, &ExchangeSplit::route);
  if (sent_ + list_.size() != std::size_t(s.n_owned))
    throw std::runtime_error(std::to_string(std::size_t(s.n_owned) - sent_ - list_.size()) +
                             " particle(s) moved from rank " + std::to_string(rank()) +
                             " into the region of a rank that is not its neighbour (they moved too far in one step)");
  if (list_.size() != std::size_t(s.n_owned)) k.keep_owned(s, list_);
  unpack(k, s, arrived, false);
}

void DomainExchange::migrate(ParticleStore& s, ParticleMovement& k) {
  send_to_owners(s, k, peers_);
}

void DomainExchange::refresh_ghosts(ParticleStore& s, ParticleMovement& k) {
  s.drop_ghosts();
  last_lap_ = std::chrono::steady_clock::now();
  // Decomposition::neighbours() holds every rank within the halo of an owned
  // particle, so no ghost is tagged for a rank that is not a peer.
  router(s, peers_).tag_ghosts(s, reach());
  lap(k, &ExchangeSplit::route);
  const std::vector<MessageHeader> arrived = trade(k, s, peers_, false);
  ghost_first_.assign(peers_.size(), 0);
  ghost_count_.assign(peers_.size(), 0);
  Index at = s.n_owned;
  for (std::size_t p = 0; p < peers_.size(); ++p) {
    ghost_first_[p] = at;
    ghost_count_[p] = Index(arrived[p].count);
    at += ghost_count_[p];
  }
  unpack(k, s, arrived, true);
  plan_revision_ = s.revision;
  plan_valid_ = true;
  ++split_.rebuilds;
}

bool DomainExchange::rebalance(ParticleStore& s, ParticleMovement& k) {
  if (ranks() == 1) return false;
  std::vector<std::int64_t> loads(std::size_t(ranks()), 0);
  loads[std::size_t(rank())] = s.n_owned;
  transport_.sum(loads);
  if (load_imbalance(loads) <= spec_.rebalance_threshold) return false;

  const std::vector<Vec3d> x = owned_positions(s);
  const CoarseGrid& grid = decomposition_->grid();
  if (auto* slabs = dynamic_cast<SlabDecomposition*>(decomposition_.get())) {
    Histogram h = layer_histogram(grid, slabs->axis(), x);
    transport_.sum(h);
    slabs->rebalance(h);
  } else if (auto* metis = dynamic_cast<MetisDecomposition*>(decomposition_.get())) {
    Histogram h = cell_histogram(grid, x);
    transport_.sum(h);
    metis->rebalance(h);
  }
  map_current_ = false;
  peers_ = neighbours();
  send_to_owners(s, k, all_other_ranks());
  return true;
}

std::string DomainExchange::first_fault(const std::string& local) {
  const int first = transport_.min(local.empty() ? INT_MAX : rank());
  if (first == INT_MAX) return "";
  const Bytes text = transport_.broadcast(Bytes(local.begin(), local.end()), first);
  return "rank " + std::to_string(first) + ": " + std::string(text.begin(), text.end());
}

long long DomainExchange::total(long long local) {
  std::vector<std::int64_t> v{local};
  transport_.sum(v);
  return v[0];
}

}  // namespace gs
