// Pack and unpack: particles selected by index, with their contact history,
// go through one message in backend memory and arrive bit for bit, on every
// backend and for each history layout (friction, + rolling, fp32 and fp64).
#include <gtest/gtest.h>

#include <cstring>

#include "engine/step_kernels.hpp"
#include "support/support.hpp"

namespace gs {
namespace {

constexpr int kSlots = 4;

ParticleRecords sample_records(std::size_t n, bool rolling) {
  ParticleRecords r;
  r.history.slots = kSlots;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = double(i) + 0.1234567891234;
    r.id.push_back(ParticleId(1000 + 7 * i));
    r.material.push_back(std::uint8_t(i % 2));
    r.marker.push_back(std::uint8_t(i % 3));
    r.radius.push_back(float(0.001 * f));
    r.mass.push_back(float(2 * f));
    r.inertia.push_back(float(3 * f));
    r.position.emplace_back(f, -f / 3, f / 7);
    r.velocity.emplace_back(f / 11, f / 13, -f / 17);
    r.angular_velocity.emplace_back(-f / 19, f / 23, f / 29);
    r.orientation.push_back({float(f), float(-f), float(f / 3), float(f / 5)});
    for (int s = 0; s < kSlots; ++s) {
      const bool used = (i + std::size_t(s)) % 3 != 0;
      r.history.partner.push_back(used ? ParticleId(5 * i + std::size_t(s)) : kNoPartner);
      // Values exact in fp32, so every precision carries them unchanged.
      r.history.tangential.emplace_back(0.25 * s + double(i), -0.5 * double(i), 0.125);
      if (rolling) r.history.rolling.emplace_back(0.0625 * double(i), 0.75 * s, -1.0);
    }
  }
  return r;
}

ParticleStore empty_store(Backend b) {
  ParticleStore s;
  s.backend = b;
  s.id = DeviceArray<ParticleId>(b);
  s.material = DeviceArray<std::uint8_t>(b);
  s.marker = DeviceArray<std::uint8_t>(b);
  s.radius = DeviceArray<float>(b);
  s.mass = DeviceArray<float>(b);
  s.inertia = DeviceArray<float>(b);
  s.position = DeviceArray<Vec3d>(b);
  s.velocity = DeviceArray<Vec3d>(b);
  s.angular_velocity = DeviceArray<Vec3d>(b);
  s.orientation = DeviceArray<Quaternion>(b);
  return s;
}

template <class T>
std::vector<T> picked(const std::vector<T>& v, const std::vector<Index>& which, std::size_t per = 1) {
  std::vector<T> out;
  for (Index i : which)
    for (std::size_t k = 0; k < per; ++k) out.push_back(v[std::size_t(i) * per + k]);
  return out;
}

bool same_bits(const void* a, const void* b, std::size_t bytes) { return std::memcmp(a, b, bytes) == 0; }
template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && same_bits(a.data(), b.data(), a.size() * sizeof(T));
}

struct Case {
  Precision precision;
  unsigned effects;
};

class MessageTest : public testing::TestWithParam<Backend> {
 protected:
  void round_trip(const Case& c) {
    const Backend b = GetParam();
    const KernelChoice choice{b, c.precision, ContactModel::linear, c.effects};
    const PairTableHost pairs = make_pair_table(test::base_scene(2500, 1e4, 0.5, 0.5));
    auto from = make_step_kernels(choice, pairs, kSlots);
    auto to = make_step_kernels(choice, pairs, kSlots);
    const bool rolling = (c.effects & kRollingResistance) != 0;
    const ParticleRecords all = sample_records(50, rolling);
    ParticleStore a = empty_store(b), z = empty_store(b);
    from->append(a, all, false);
    // z already holds particles: arrivals go after them.
    const ParticleRecords first = sample_records(3, rolling);
    to->append(z, first, false);

    const std::vector<Index> which{49, 3, 17, 0, 18, 31};
    DeviceArray<Index> w(b);
    w.from_host(which);
    DeviceArray<unsigned char> message(b);
    const MessageHeader h = from->pack(a, w, true, message);
    EXPECT_EQ(h.count, which.size());
    EXPECT_EQ(message.size(), MessageLayout(h).bytes);
    to->unpack(z, h, message.data(), false);

    ASSERT_EQ(z.n_owned, Index(3 + which.size()));
    std::vector<Index> arrived(which.size());
    for (std::size_t k = 0; k < which.size(); ++k) arrived[k] = Index(3 + k);
    EXPECT_TRUE(same(picked(z.id.to_host(), arrived), picked(all.id, which)));
    EXPECT_TRUE(same(picked(z.material.to_host(), arrived), picked(all.material, which)));
    EXPECT_TRUE(same(picked(z.marker.to_host(), arrived), picked(all.marker, which)));
    EXPECT_TRUE(same(picked(z.radius.to_host(), arrived), picked(all.radius, which)));
    EXPECT_TRUE(same(picked(z.mass.to_host(), arrived), picked(all.mass, which)));
    EXPECT_TRUE(same(picked(z.inertia.to_host(), arrived), picked(all.inertia, which)));
    EXPECT_TRUE(same(picked(z.position.to_host(), arrived), picked(all.position, which)));
    EXPECT_TRUE(same(picked(z.velocity.to_host(), arrived), picked(all.velocity, which)));
    EXPECT_TRUE(same(picked(z.angular_velocity.to_host(), arrived), picked(all.angular_velocity, which)));
    EXPECT_TRUE(same(picked(z.orientation.to_host(), arrived), picked(all.orientation, which)));
    const HostHistory got = to->history(z);
    EXPECT_TRUE(same(picked(got.partner, arrived, kSlots), picked(all.history.partner, which, kSlots)));
    EXPECT_TRUE(same(picked(got.tangential, arrived, kSlots), picked(all.history.tangential, which, kSlots)));
    if (rolling) {
      EXPECT_TRUE(same(picked(got.rolling, arrived, kSlots), picked(all.history.rolling, which, kSlots)));
    }
    // The particles that were there stay as they were.
    EXPECT_TRUE(same(picked(got.partner, {0, 1, 2}, kSlots), first.history.partner));

    // As ghosts: no history travels, and a header claiming other history is refused.
    const MessageHeader g = from->pack(a, w, false, message);
    EXPECT_EQ(g.slots, 0);
    EXPECT_THROW(to->unpack(z, g, message.data(), false), std::runtime_error);
    to->unpack(z, g, message.data(), true);
    EXPECT_EQ(z.n_ghost, Index(which.size()));
    MessageHeader bad = h;
    bad.check ^= 1u;
    EXPECT_THROW(to->unpack(z, bad, message.data(), true), std::runtime_error);
  }
};

TEST_P(MessageTest, FrictionFp32) { round_trip({Precision::fp32, kFriction}); }
TEST_P(MessageTest, FrictionAndRollingFp64) { round_trip({Precision::fp64, kFriction | kRollingResistance}); }

INSTANTIATE_TEST_SUITE_P(Backends, MessageTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
