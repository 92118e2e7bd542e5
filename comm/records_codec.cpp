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
  put(out, r.id);
  put(out, r.material);
  put(out, r.marker);
  put(out, r.radius);
  put(out, r.mass);
  put(out, r.inertia);
  put(out, r.position);
  put(out, r.velocity);
  put(out, r.angular_velocity);
  put(out, r.orientation);
  put(out, std::vector<std::int32_t>{r.history.slots});
  put(out, r.history.partner);
  put(out, r.history.tangential);
  put(out, r.history.rolling);
}

ParticleRecords decode_records(const Bytes& in) {
  ParticleRecords r;
  if (in.empty()) return r;
  Reader read(in);
  read.get(r.id);
  read.get(r.material);
  read.get(r.marker);
  read.get(r.radius);
  read.get(r.mass);
  read.get(r.inertia);
  read.get(r.position);
  read.get(r.velocity);
  read.get(r.angular_velocity);
  read.get(r.orientation);
  std::vector<std::int32_t> slots;
  read.get(slots);
  r.history.slots = slots.empty() ? 0 : slots[0];
  read.get(r.history.partner);
  read.get(r.history.tangential);
  read.get(r.history.rolling);
  if (!read.done()) throw std::runtime_error("particle message has trailing bytes");
  return r;
}

void append_records(ParticleRecords& into, const ParticleRecords& more) {
  if (more.size() == 0) return;
  if (into.size() == 0) into.history.slots = more.history.slots;
  if (into.history.slots != more.history.slots) throw std::logic_error("appending records with other history slots");
  extend(into.id, more.id);
  extend(into.material, more.material);
  extend(into.marker, more.marker);
  extend(into.radius, more.radius);
  extend(into.mass, more.mass);
  extend(into.inertia, more.inertia);
  extend(into.position, more.position);
  extend(into.velocity, more.velocity);
  extend(into.angular_velocity, more.angular_velocity);
  extend(into.orientation, more.orientation);
  extend(into.history.partner, more.history.partner);
  extend(into.history.tangential, more.history.tangential);
  extend(into.history.rolling, more.history.rolling);
}

}  // namespace gs
