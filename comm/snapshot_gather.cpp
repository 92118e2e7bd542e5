#include "comm/snapshot_gather.hpp"

#include "comm/records_codec.hpp"
#include "core/id_order.hpp"

#include <cstring>
#include <stdexcept>

namespace gs {
namespace {

// Each field of a snapshot, visited in one fixed order for packing and
// unpacking: the particle fields in their declared order, then the forces
// and the contact counts. An optional field not kept travels empty.
template <class Snapshot, class F>
void for_each_field(Snapshot& s, F&& f) {
  for_each_particle_field(s, [&](const char*, auto& v) { f(v); });
  f(s.force);
  f(s.torque);
  f(s.contacts);
}

Bytes pack(const ParticleSnapshot& s) {
  Bytes out;
  for_each_field(s, [&](auto& v) {
    const std::uint64_t n = v.size();
    const std::size_t at = out.size(), bytes = n * sizeof(v[0]);
    out.resize(at + sizeof(n) + bytes);
    std::memcpy(out.data() + at, &n, sizeof(n));
    if (bytes > 0) std::memcpy(out.data() + at + sizeof(n), v.data(), bytes);
  });
  return out;
}

void unpack_append(const Bytes& in, ParticleSnapshot& into) {
  std::size_t at = 0;
  for_each_field(into, [&](auto& v) {
    std::uint64_t n = 0;
    if (at + sizeof(n) > in.size()) throw std::runtime_error("snapshot message truncated");
    std::memcpy(&n, in.data() + at, sizeof(n));
    at += sizeof(n);
    const std::size_t old = v.size(), bytes = n * sizeof(v[0]);
    if (at + bytes > in.size()) throw std::runtime_error("snapshot message truncated");
    v.resize(old + n);
    if (bytes > 0) std::memcpy(v.data() + old, in.data() + at, bytes);
    at += bytes;
  });
}

template <class T>
void permute(std::vector<T>& v, const std::vector<std::size_t>& order) {
  if (!v.empty()) v = permuted(v, order);
}

// Every rank's packed part into `all` on rank 0, in id order.
void gather_packed(Transport& transport, Bytes packed, double time, long long step, ParticleSnapshot& all) {
  std::vector<Bytes> parts = transport.gather(std::move(packed));
  all.time = time;
  all.step = step;
  for_each_field(all, [](auto& v) { v.clear(); });  // the memory stays for the next output
  if (transport.rank() != 0) return;
  for (Bytes& b : parts) {
    unpack_append(b, all);
    Bytes().swap(b);
  }
  const std::vector<std::size_t> order = id_order(all.id);
  for_each_field(all, [&](auto& v) { permute(v, order); });
}

}  // namespace

ParticleSnapshot gather_snapshot(Transport& transport, ParticleSnapshot local) {
  if (transport.size() == 1) return local;
  Bytes packed = pack(local);
  const double time = local.time;
  const long long step = local.step;
  local = ParticleSnapshot();  // rank 0 needs the room for the whole
  ParticleSnapshot all;
  gather_packed(transport, std::move(packed), time, step, all);
  return all;
}

void gather_snapshot(Transport& transport, const ParticleSnapshot& local, ParticleSnapshot& all) {
  if (transport.size() == 1) {
    if (&all != &local) all = local;
    return;
  }
  gather_packed(transport, pack(local), local.time, local.step, all);
}

HostHistory gather_history(Transport& transport, const std::vector<ParticleId>& local_ids, const HostHistory& local) {
  if (transport.size() == 1) return local;
  HostHistory all;
  gather_history(transport, local_ids, local, all);
  return all;
}

void gather_history(Transport& transport, const std::vector<ParticleId>& local_ids, const HostHistory& local,
                    HostHistory& all) {
  if (transport.size() == 1) {
    if (&all != &local) all = local;
    return;
  }
  ParticleRecords mine;
  mine.id = local_ids;
  mine.history = local;
  all = gather_history_records(transport, mine).history;
}

ParticleRecords gather_history_records(Transport& transport, const ParticleRecords& local) {
  if (transport.size() == 1) return local;
  Bytes bytes;
  encode_records(local, bytes);
  ParticleRecords all;
  for (const Bytes& b : transport.gather(bytes)) append_records(all, decode_records(b));
  ParticleRecords out;
  out.history.slots = local.history.slots;
  if (transport.rank() != 0) return out;
  const std::vector<std::size_t> order = id_order(all.id);
  out.id = permuted(all.id, order);
  out.history = rows_permuted(all.history, order);
  return out;
}

}  // namespace gs
