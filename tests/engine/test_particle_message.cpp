// Pack and unpack: particles selected by index, with their contact history,
// go through one message in backend memory and arrive bit for bit (a row of
// contacts with its empty entries after them), on every backend and for each
// history layout (friction, + rolling, the hysteretic model's peak overlaps;
// fp32 and fp64).
#include <gtest/gtest.h>

#include <cstring>
#include <type_traits>

#include "contact/contact_models.hpp"
#include "engine/step_kernels.hpp"
#include "support/support.hpp"

namespace gs {
namespace {

constexpr int kSlots = 4;

// Values exact in fp32, so every precision carries them unchanged.
void sample_value(Vec3d& v, double a, double b) { v = {a, -0.5 * b, 0.125}; }
void sample_value(double& v, double a, double b) { v = a + 0.25 * b; }

// n particles with every field, and the history fields `kept` (HistoryField bits).
ParticleRecords sample_records(std::size_t n, unsigned kept) {
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
      for_each_history_field(r.history, [&](const char*, unsigned bit, auto& field) {
        if (!(kept & bit)) return;
        field.emplace_back();
        sample_value(field.back(), 0.25 * s + double(i) + bit, double(i));
      });
    }
  }
  return r;
}

ParticleStore empty_store(Backend b) {
  ParticleStore s;
  s.place_on(b);
  return s;
}

template <class T>
std::vector<T> picked(const std::vector<T>& v, const std::vector<Index>& which, std::size_t per = 1) {
  std::vector<T> out;
  for (Index i : which)
    for (std::size_t k = 0; k < per; ++k) out.push_back(v[std::size_t(i) * per + k]);
  return out;
}

// Rows of `per` entries as a row of particle pairs is given back after it
// arrived (engine/pair_history.hpp): its contacts in the order they came,
// then the empty entries (kNoPartner, zero values). `partner` names them.
template <class T>
std::vector<T> closed(const std::vector<T>& rows, const std::vector<ParticleId>& partner, std::size_t per, T empty) {
  std::vector<T> out;
  for (std::size_t r = 0; r < rows.size() / per; ++r) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < per; ++k)
      if (partner[r * per + k] != kNoPartner) out.push_back(rows[r * per + k]), ++n;
    for (; n < per; ++n) out.push_back(empty);
  }
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
  ContactModel model = ContactModel::linear;
};

class MessageTest : public testing::TestWithParam<Backend> {
 protected:
  void round_trip(const Case& c) {
    const Backend b = GetParam();
    const KernelChoice choice{b, c.precision, c.model, c.effects};
    const SceneSpec scene = test::base_scene(2500, 1e4, 0.5, 0.5);
    const ContactInputs pairs{scene.materials, scene.pairs, kSlots};
    auto from = make_step_kernels(choice, pairs);
    auto to = make_step_kernels(choice, pairs);
    const unsigned kept = history_fields_kept(c.model, c.effects);
    const ParticleRecords all = sample_records(50, kept);
    ParticleStore a = empty_store(b), z = empty_store(b);
    from->movement().append(a, all, false);
    // z already holds particles: arrivals go after them.
    const ParticleRecords first = sample_records(3, kept);
    to->movement().append(z, first, false);

    const std::vector<Index> which{49, 3, 17, 0, 18, 31};
    DeviceArray<Index> w(b);
    w.from_host(which);
    DeviceArray<unsigned char> message(b);
    const MessageHeader h = from->movement().pack(a, w, true, message);
    EXPECT_EQ(h.count, which.size());
    EXPECT_EQ(message.size(), MessageLayout(h).bytes);
    to->movement().unpack(z, h, message.data(), false);

    ASSERT_EQ(z.n_owned, Index(3 + which.size()));
    std::vector<Index> arrived(which.size());
    for (std::size_t k = 0; k < which.size(); ++k) arrived[k] = Index(3 + k);
    for_each_kept_particle_field(z, all, z.fields_kept, [&](const char* name, const auto& field, const auto& sent) {
      EXPECT_TRUE(same(picked(field.to_host(), arrived), picked(sent, which))) << name;
    });
    // Their rows as they came, the empty entries after the contacts (the
    // sample's rows have holes).
    const HostHistory got = to->movement().history(z);
    const std::vector<ParticleId> sent_partner = picked(all.history.partner, which, kSlots);
    EXPECT_TRUE(same(picked(got.partner, arrived, kSlots), closed(sent_partner, sent_partner, kSlots, kNoPartner)));
    for_each_history_field(got, all.history, [&](const char* name, unsigned bit, const auto& field, const auto& sent) {
      EXPECT_EQ(field.empty(), !(kept & bit)) << name;
      if (kept & bit) {
        using T = typename std::decay_t<decltype(field)>::value_type;
        const std::vector<T> want = closed(picked(sent, which, kSlots), sent_partner, kSlots, T{});
        EXPECT_TRUE(same(picked(field, arrived, kSlots), want)) << name;
      }
    });
    // The particles that were there stay as they were.
    EXPECT_TRUE(same(picked(got.partner, {0, 1, 2}, kSlots),
                     closed(first.history.partner, first.history.partner, kSlots, kNoPartner)));

    // As ghosts: no history travels, and a header claiming other history is refused.
    const MessageHeader g = from->movement().pack(a, w, false, message);
    EXPECT_EQ(g.slots, 0);
    EXPECT_THROW(to->movement().unpack(z, g, message.data(), false), std::runtime_error);
    to->movement().unpack(z, g, message.data(), true);
    EXPECT_EQ(z.n_ghost, Index(which.size()));
    MessageHeader bad = h;
    bad.check ^= 1u;
    EXPECT_THROW(to->movement().unpack(z, bad, message.data(), true), std::runtime_error);
  }
};

TEST_P(MessageTest, FrictionFp32) { round_trip({Precision::fp32, kFriction}); }
TEST_P(MessageTest, FrictionAndRollingFp64) { round_trip({Precision::fp64, kFriction | kRollingResistance}); }
// The hysteretic model's peak overlaps, alone and with the springs.
TEST_P(MessageTest, PeakOverlapFp32) { round_trip({Precision::fp32, 0, ContactModel::hysteretic_linear}); }
TEST_P(MessageTest, PeakOverlapAndFrictionFp64) {
  round_trip({Precision::fp64, kFriction, ContactModel::hysteretic_linear});
}

INSTANTIATE_TEST_SUITE_P(Backends, MessageTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
