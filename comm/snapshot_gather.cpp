#include "comm/snapshot_gather.hpp"

#include "comm/records_codec.hpp"
#include "core/id_order.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

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

// The arrays visit(f) hands to f, one after the other, each as its count
// (uint64) and its values: one allocation, not one per array.
template <class Visit>
Bytes pack_arrays(Visit&& visit) {
  std::size_t size = 0;
  visit([&](const auto& v) { size += sizeof(std::uint64_t) + v.size() * sizeof(v[0]); });
  Bytes out(size);
  std::size_t at = 0;
  visit([&](const auto& v) {
    const std::uint64_t n = v.size();
    const std::size_t bytes = n * sizeof(v[0]);
    std::memcpy(out.data() + at, &n, sizeof(n));
    if (bytes > 0) std::memcpy(out.data() + at + sizeof(n), v.data(), bytes);
    at += sizeof(n) + bytes;
  });
  return out;
}

Bytes pack(const ParticleSnapshot& s) {
  return pack_arrays([&](auto&& f) { for_each_field(s, f); });
}

// Reads the row count of the next field of each part, at the parts' cursors.
std::vector<std::uint64_t> next_counts(const std::vector<Bytes>& parts, std::vector<std::size_t>& at) {
  std::vector<std::uint64_t> n(parts.size());
  for (std::size_t p = 0; p < parts.size(); ++p) {
    if (at[p] + sizeof(std::uint64_t) > parts[p].size()) throw std::runtime_error("snapshot message truncated");
    std::memcpy(&n[p], parts[p].data() + at[p], sizeof(std::uint64_t));
    at[p] += sizeof(std::uint64_t);
  }
  return n;
}

// The next array of every part at the parts' cursors: rows of `width`
// values, row k of the parts (one after another) to row place[k] of `v`,
// which is resized to hold them (an array not kept travels empty: `v` empty).
template <class T>
void unpack_rows(const std::vector<Bytes>& parts, std::vector<std::size_t>& at, const std::vector<std::size_t>& place,
                 std::size_t width, std::vector<T>& v) {
  const std::vector<std::uint64_t> n = next_counts(parts, at);
  std::size_t total = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    total += n[p];
    if (at[p] + n[p] * sizeof(T) > parts[p].size()) throw std::runtime_error("snapshot message truncated");
  }
  if (total != 0 && total != place.size() * width) throw std::runtime_error("snapshot message: an array has another row count");
  v.resize(total);
  const std::size_t row_bytes = width * sizeof(T);
  for (std::size_t p = 0, row = 0; p < parts.size(); ++p) {
    const char* from = parts[p].data() + at[p];
    const auto m = static_cast<std::ptrdiff_t>(width > 0 ? n[p] / width : 0);
#pragma omp parallel for schedule(static) if (m > 100000)
    for (std::ptrdiff_t j = 0; j < m; ++j)
      std::memcpy(&v[place[row + std::size_t(j)] * width], from + std::size_t(j) * row_bytes, row_bytes);
    at[p] += n[p] * sizeof(T);
    row += std::size_t(m);
  }
}

// The first array of every part, ids (the cursors move past them):
// place[k], the row in id order of row k of the parts one after another.
std::vector<std::size_t> id_places(const std::vector<Bytes>& parts, std::vector<std::size_t>& at) {
  const std::vector<std::uint64_t> n = next_counts(parts, at);
  std::size_t total = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    total += n[p];
    if (at[p] + n[p] * sizeof(ParticleId) > parts[p].size()) throw std::runtime_error("snapshot message truncated");
  }
  std::vector<ParticleId> ids(total);
  for (std::size_t p = 0, row = 0; p < parts.size(); row += n[p], ++p) {
    if (n[p] > 0) std::memcpy(ids.data() + row, parts[p].data() + at[p], n[p] * sizeof(ParticleId));
    at[p] += n[p] * sizeof(ParticleId);
  }
  const std::vector<std::size_t> order = id_order(ids);
  std::vector<std::size_t> place(total);
  for (std::size_t r = 0; r < total; ++r) place[order[r]] = r;
  return place;
}

// Every rank's packed part into `all` on rank 0, in id order. The parts'
// ids give the order; each field's rows then go straight from the messages
// to their place in `all`'s arrays (kept from the last call): one pass, no
// concatenated copy to permute.
void gather_packed(Transport& transport, Bytes packed, double time, long long step, ParticleSnapshot& all) {
  std::vector<Bytes> parts = transport.gather(std::move(packed));
  all.time = time;
  all.step = step;
  if (transport.rank() != 0) {
    for_each_field(all, [](auto& v) { v.clear(); });
    return;
  }
  std::vector<std::size_t> at(parts.size(), 0);
  std::vector<std::size_t> ids_at = at;
  const std::vector<std::size_t> place = id_places(parts, ids_at);  // the ids are the first field
  for_each_field(all, [&](auto& v) { unpack_rows(parts, at, place, 1, v); });
}

// Each array of a rank's history part: its ids, then the partners and the
// history fields (one not kept travels empty).
template <class Ids, class History, class F>
void for_each_history_array(Ids& ids, History& h, F&& f) {
  f(ids);
  f(h.partner);
  for_each_history_field(h, [&](const char*, unsigned, auto& v) { f(v); });
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

// Each rank's rows go straight from its message to their place in id order
// in `all`'s arrays (kept from the last call), as gather_packed does: no
// copy of the whole history appended, decoded or permuted on rank 0.
void gather_history(Transport& transport, const std::vector<ParticleId>& local_ids, const HostHistory& local,
                    HostHistory& all) {
  if (transport.size() == 1) {
    if (&all != &local) all = local;
    return;
  }
  std::vector<Bytes> parts = transport.gather(pack_arrays([&](auto&& f) { for_each_history_array(local_ids, local, f); }));
  all.slots = local.slots;  // the same on every rank (the scene's)
  std::vector<ParticleId> no_ids;
  if (transport.rank() != 0) {
    for_each_history_array(no_ids, all, [](auto& v) { v.clear(); });
    return;
  }
  std::vector<std::size_t> at(parts.size(), 0);
  const std::vector<std::size_t> place = id_places(parts, at);
  const std::size_t width = std::size_t(std::max(0, all.slots));
  unpack_rows(parts, at, place, width, all.partner);
  for_each_history_field(all, [&](const char*, unsigned, auto& v) { unpack_rows(parts, at, place, width, v); });
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
