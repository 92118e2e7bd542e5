#include "comm/records_codec.hpp"

#include <cstring>
#include <stdexcept>

namespace gs {
namespace {

template <class T>
void put(Bytes& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  const std::size_t at = out.size();
  out.resize(at + sizeof(n) + n * sizeof(T));
  std::memcpy(out.data() + at, &n, sizeof(n));
  if (n > 0) std::memcpy(out.data() + at + sizeof(n), v.data(), n * sizeof(T));
}

class Reader {
 public:
  explicit Reader(const Bytes& in) : in_(in) {}
  template <class T>
  void get(std::vector<T>& v) {
    std::uint64_t n = 0;
    take(&n, sizeof(n));
    v.resize(n);
    take(v.data(), n * sizeof(T));
  }
  void take(void* to, std::size_t bytes) {
    if (at_ + bytes > in_.size()) throw std::runtime_error("particle message truncated");
    if (bytes > 0) std::memcpy(to, in_.data() + at_, bytes);
    at_ += bytes;
  }
  bool done() const { return at_ == in_.size(); }

 private:
  const Bytes& in_;
  std::size_t at_ = 0;
};

template <class T>
void extend(std::vector<T>& a, const std::vector<T>& b) {
  a.insert(a.end(), b.begin(), b.end());
}

}  // namespace

void encode_records(const ParticleRecords& r, Bytes& out) {
  out.clear();
  for_each_particle_field(r, [&](const char*, const auto& field) { put(out, field); });
  put(out, std::vector<std::int32_t>{r.history.slots});
  put(out, r.history.partner);
  for_each_history_field(r.history, [&](const char*, unsigned, const auto& field) { put(out, field); });
}

ParticleRecords decode_records(const Bytes& in) {
  ParticleRecords r;
  if (in.empty()) return r;
  Reader read(in);
  for_each_particle_field(r, [&](const char*, auto& field) { read.get(field); });
  std::vector<std::int32_t> slots;
  read.get(slots);
  r.history.slots = slots.empty() ? 0 : slots[0];
  read.get(r.history.partner);
  for_each_history_field(r.history, [&](const char*, unsigned, auto& field) { read.get(field); });
  if (!read.done()) throw std::runtime_error("particle message has trailing bytes");
  return r;
}

void append_records(ParticleRecords& into, const ParticleRecords& more) {
  if (more.size() == 0) return;
  if (into.size() == 0) into.history.slots = more.history.slots;
  if (into.history.slots != more.history.slots) throw std::logic_error("appending records with other history slots");
  for_each_particle_field(into, more, [](const char*, auto& to, const auto& from) { extend(to, from); });
  extend(into.history.partner, more.history.partner);
  for_each_history_field(into.history, more.history, [](const char*, unsigned, auto& to, const auto& from) {
    extend(to, from);
  });
}

}  // namespace gs
