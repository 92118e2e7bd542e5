// The kept table of a list rebuild (engine/pair_keep.hpp), against contacts
// listed by hand: a particle's touching contacts come out of its carried row
// in ascending partner id, and out of a pending row (an arrival's pair
// contacts in the order they came: engine/pair_history.hpp) sorted by
// partner id; the new list's entries then find the springs of their partner,
// and zero where it did not touch. Each pass also by groups of 1 to 8 host
// threads playing a GPU's lanes (support/thread_lanes.hpp): the same tables.
// And the pending table itself: arriving rows leave their pair contacts
// there and their surface contacts to the surface table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "backend/cpu/cpu_exec.hpp"
#include "engine/pair_keep.hpp"
#include "support/thread_lanes.hpp"

namespace gs::test {
namespace {

// m arriving rows of `width`, a slot-major block (entry s of row k at s * m
// + k, as PairCarry::arrive takes them), appended to a pending table.
template <class T>
void pend(std::vector<ListOffset>& begin, std::vector<ParticleId>& partner, std::vector<T>& field,
          const std::vector<ParticleId>& rows, const std::vector<T>& values, int width) {
  const Index m = Index(rows.size()) / width;
  const ArrivingRows arriving{rows.data(), width, m};
  const Index row0 = begin.empty() ? 0 : Index(begin.size()) - 1;
  begin.resize(std::size_t(row0 + m) + 1);
  ListOffset* at = begin.data() + row0;
  CpuExec::parallel_for(m, CountArrivingPairs{arriving, at, ListOffset(partner.size())});
  DeviceArray<unsigned char> scratch(Backend::cpu);
  const ListOffset total = CpuExec::scan_counts(at, m, scratch, "the test's pending rows");
  partner.resize(total);
  field.resize(total);
  CpuExec::parallel_for(m, PairsToPending<ParticleId>{arriving, rows.data(), partner.data(), at});
  CpuExec::parallel_for(m, PairsToPending<T>{arriving, values.data(), field.data(), at});
}

// Three owned particles: 0 from carried row 1, 1 from pending row 0, 2 new.
// Carried row 1 lists partners 3, 5, 8, 9 (5 and 9 not touching); the row
// that arrived (width 5) held partner 7, a wall, 4, an empty entry and
// partner 6, of which the pending table keeps 7, 4 and 6.
struct Detached {
  std::vector<Index> origin{1, kPendingBase + 0};  // particle 2 has none (beyond)
  std::vector<ListOffset> carried_begin{0, 2, 6};
  std::vector<Index> carried_partner{11, 12, 3, 5, 8, 9};
  std::vector<std::uint8_t> carried_touching{1, 1, 1, 0, 1, 0};
  std::vector<float> carried_spring{-1, -2, 30, 0, 80, 0};  // a scalar field (peak_overlap's place)
  std::vector<Vec3f> carried_tangential{{-1, 0, 0}, {-2, 0, 0}, {3, 1, 0}, {}, {8, 0, 1}, {}};
  std::vector<ListOffset> pending_begin;
  std::vector<ParticleId> pending_partner;
  std::vector<float> pending_spring;
  std::vector<Vec3f> pending_tangential;
  Detached() {
    const std::vector<ParticleId> row{7, kWallPartnerBase + 2, 4, kNoPartner, 6};
    std::vector<ListOffset> begin;
    std::vector<ParticleId> partner;
    pend(pending_begin, pending_partner, pending_spring, row, {70, 99, 40, 0, 60}, 5);
    pend(begin, partner, pending_tangential, row, {{7, 0, 0}, {9, 9, 9}, {4, 0, 0}, {}, {6, 0, 0}}, 5);
  }
  DetachedContacts contacts() const {
    const DetachedTables tables{origin.data(),           Index(origin.size()), carried_begin.data(),
                                carried_partner.data(),  carried_touching.data(), pending_begin.data(),
                                pending_partner.data()};
    return {tables};
  }
};

std::vector<ListOffset> counted(const Detached& d, Index n) {
  std::vector<ListOffset> begin(std::size_t(n) + 1, 99);
  CpuExec::parallel_for(n, CountKept{d.contacts(), begin.data()});
  DeviceArray<unsigned char> scratch(Backend::cpu);
  const ListOffset total = CpuExec::scan_counts(begin.data(), n, scratch, "the test's kept table");
  EXPECT_EQ(total, begin[std::size_t(n)]);
  return begin;
}

// Runs pass f over particles [0, n): each particle by one lane (operator()),
// then by groups of 2, 4 and 8 lanes; `check` after each.
template <class F, class Reset, class Check>
void each_way(Index n, const F& f, const Reset& reset, const Check& check) {
  reset();
  CpuExec::parallel_for(n, f);
  check(1);
  for (int lanes : {2, 4, 8}) {
    reset();
    for (Index i = 0; i < n; ++i) run_lanes(lanes, [&](const ThreadLane& g) { f.in_group(i, g); });
    check(lanes);
  }
}

TEST(PairKeep, TouchingContactsInAscendingPartnerId) {
  Detached d;
  const std::vector<ListOffset> begin = counted(d, 3);
  EXPECT_EQ(begin, (std::vector<ListOffset>{0, 2, 5, 5}));  // 2 carried, 3 pending, none
  std::vector<ParticleId> partner(5);
  std::vector<float> spring(5);
  std::vector<Vec3f> tangential(5);
  FieldArrays<float> to, carried, pending;
  to.peak_overlap = spring.data();
  to.tangential = tangential.data();
  carried.peak_overlap = d.carried_spring.data();
  carried.tangential = d.carried_tangential.data();
  pending.peak_overlap = d.pending_spring.data();
  pending.tangential = d.pending_tangential.data();
  const KeepContacts<float> keep{d.contacts(), begin.data(), partner.data(), to, carried, pending};
  each_way(
      3, keep,
      [&] {
        std::fill(partner.begin(), partner.end(), 99);
        std::fill(spring.begin(), spring.end(), -9.0f);
        std::fill(tangential.begin(), tangential.end(), Vec3f(-9, -9, -9));
      },
      [&](int lanes) {
        EXPECT_EQ(partner, (std::vector<ParticleId>{3, 8, 4, 6, 7})) << lanes << " lanes";
        EXPECT_EQ(spring, (std::vector<float>{30, 80, 40, 60, 70})) << lanes << " lanes";
        const std::vector<float> x{3, 8, 4, 6, 7}, y{1, 0, 0, 0, 0}, z{0, 1, 0, 0, 0};
        for (std::size_t k = 0; k < 5; ++k) {
          EXPECT_EQ(tangential[k].x, x[k]) << lanes << " lanes, entry " << k;
          EXPECT_EQ(tangential[k].y, y[k]) << lanes << " lanes, entry " << k;
          EXPECT_EQ(tangential[k].z, z[k]) << lanes << " lanes, entry " << k;
        }
      });
}

// A carried row longer than the lanes (10 entries, touching at 0, 3, 4, 8
// and 9): a group of 2 or 4 lanes takes several rounds, and the touching
// entries of a round land after those of the rounds before.
TEST(PairKeep, LongRowsTakeSeveralRoundsOfLanes) {
  Detached d;
  d.origin = {0};
  d.carried_begin = {0, 10};
  d.carried_partner = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  d.carried_touching = {1, 0, 0, 1, 1, 0, 0, 0, 1, 1};
  d.carried_spring = {10, 0, 0, 40, 50, 0, 0, 0, 90, 100};
  const std::vector<ListOffset> begin = counted(d, 1);
  ASSERT_EQ(begin, (std::vector<ListOffset>{0, 5}));
  std::vector<ParticleId> partner(5);
  std::vector<float> spring(5);
  FieldArrays<float> to, carried, pending;
  carried.peak_overlap = d.carried_spring.data();
  to.peak_overlap = spring.data();
  const KeepContacts<float> keep{d.contacts(), begin.data(), partner.data(), to, carried, pending};
  each_way(
      1, keep,
      [&] {
        std::fill(partner.begin(), partner.end(), 0);
        std::fill(spring.begin(), spring.end(), 0.0f);
      },
      [&](int lanes) {
        EXPECT_EQ(partner, (std::vector<ParticleId>{1, 4, 5, 9, 10})) << lanes << " lanes";
        EXPECT_EQ(spring, (std::vector<float>{10, 40, 50, 90, 100})) << lanes << " lanes";
      });
}

// The new list of particle 0: partners 2, 3, 5, 8 (5 was listed, not
// touching; 2 is new); of particle 1: 4, 7 (6 left its reach); particle 2: 3.
TEST(PairKeep, NewEntriesFindTheirPartnersSprings) {
  const std::vector<ParticleId> id{0, 1, 2, 3, 4, 5, 6, 7, 8};  // store index = id here
  const std::vector<ListOffset> list_begin{0, 4, 6, 7};
  const std::vector<Index> list{2, 3, 5, 8, 4, 7, 3};
  const std::vector<ListOffset> kept_begin{0, 2, 5, 5};
  const std::vector<ParticleId> kept_partner{3, 8, 4, 6, 7};
  std::vector<float> kept_spring{30, 80, 40, 60, 70};
  std::vector<Vec3f> kept_tangential{{3, 0, 0}, {8, 0, 0}, {4, 0, 0}, {6, 0, 0}, {7, 0, 0}};
  std::vector<float> spring(7);
  std::vector<Vec3f> tangential(7);
  std::vector<std::uint8_t> touching(7);
  FieldArrays<float> kept, to;
  kept.peak_overlap = kept_spring.data();
  kept.tangential = kept_tangential.data();
  to.peak_overlap = spring.data();
  to.tangential = tangential.data();
  const MergeKept<float> merge{list_begin.data(), list.data(), id.data(), kept_begin.data(), kept_partner.data(),
                               kept, touching.data(), to};
  each_way(
      3, merge,
      [&] {
        std::fill(spring.begin(), spring.end(), -7.0f);
        std::fill(tangential.begin(), tangential.end(), Vec3f(-7, -7, -7));
        std::fill(touching.begin(), touching.end(), std::uint8_t(7));
      },
      [&](int lanes) {
        EXPECT_EQ(spring, (std::vector<float>{0, 30, 0, 80, 40, 70, 0})) << lanes << " lanes";
        EXPECT_EQ(touching, (std::vector<std::uint8_t>{0, 1, 0, 1, 1, 1, 0})) << lanes << " lanes";
        const std::vector<float> x{0, 3, 0, 8, 4, 7, 0};
        for (std::size_t k = 0; k < 7; ++k) {
          EXPECT_EQ(tangential[k].x, x[k]) << lanes << " lanes, entry " << k;
          EXPECT_EQ(tangential[k].y, 0) << lanes << " lanes, entry " << k;
        }
      });
}

// Halved rows (one rank, every partner owned): four particles whose store
// order is not their id order (ids 30, 10, 40, 20), touching pairs (30, 10),
// (30, 40) and (10, 20), each side's springs the other's negation (a zero
// component stored +0 on both sides) and the same peak overlap. Kept, each
// row holds only its partners of higher id; merged into a new list that
// also pairs 40 and 20 (new, not touching), every entry gets the springs its
// own row held, with the same bits (+0, not -0), as the whole rows give.
TEST(PairKeep, HalvedRowsKeepEachPairOnceAndMirrorIt) {
  const std::vector<ParticleId> id{30, 10, 40, 20};
  const Vec3f s3010{1.5f, 0.0f, -2.0f}, s3040{-0.25f, 4.0f, 0.0f}, s1020{0.0f, -3.0f, 8.0f};
  Detached d;
  d.origin = {0, 1, 2, 3};
  // Carried rows in ascending partner id: 30: {10, 40}; 10: {20, 30}; 40: {30}; 20: {10}.
  d.carried_begin = {0, 2, 4, 5, 6};
  d.carried_partner = {10, 40, 20, 30, 30, 10};
  d.carried_touching = {1, 1, 1, 1, 1, 1};
  d.carried_spring = {1, 2, 3, 1, 2, 3};  // the peak overlap: the same on both sides
  d.carried_tangential = {s3010, s3040, s1020, -s3010 + Vec3f(), -s3040 + Vec3f(), -s1020 + Vec3f()};
  // The new list: 30: {10, 40}; 10: {20, 30}; 40: {20, 30}; 20: {10, 40} (store indices).
  const std::vector<ListOffset> list_begin{0, 2, 4, 6, 8};
  const std::vector<Index> list{1, 2, 3, 0, 3, 0, 1, 2};
  const std::size_t entries = list.size();
  struct Merged {
    std::vector<float> spring;
    std::vector<Vec3f> tangential;
    std::vector<std::uint8_t> touching;
  };
  auto keep_and_merge = [&](bool halved, int lanes) {
    DetachedContacts contacts = d.contacts();
    if (halved) contacts.own_id = id.data();
    std::vector<ListOffset> begin(5);
    CpuExec::parallel_for(4, CountKept{contacts, begin.data()});
    DeviceArray<unsigned char> scratch(Backend::cpu);
    const ListOffset total = CpuExec::scan_counts(begin.data(), 4, scratch, "the test's kept table");
    EXPECT_EQ(total, halved ? 3u : 6u);
    std::vector<ParticleId> partner(total);
    std::vector<float> spring(total);
    std::vector<Vec3f> tangential(total);
    FieldArrays<float> kept, carried, pending;
    kept.peak_overlap = spring.data();
    kept.tangential = tangential.data();
    carried.peak_overlap = d.carried_spring.data();
    carried.tangential = d.carried_tangential.data();
    const KeepContacts<float> keep{contacts, begin.data(), partner.data(), kept, carried, pending};
    for (Index i = 0; i < 4; ++i) run_lanes(lanes, [&](const ThreadLane& g) { keep.in_group(i, g); });
    if (halved) {
      EXPECT_EQ(partner, (std::vector<ParticleId>{40, 20, 30}));  // 30's, 10's and 20's rows hold none
    }
    Merged m{std::vector<float>(entries, -7), std::vector<Vec3f>(entries, Vec3f(-7, -7, -7)),
             std::vector<std::uint8_t>(entries, 7)};
    FieldArrays<float> to;
    to.peak_overlap = m.spring.data();
    to.tangential = m.tangential.data();
    const MergeKept<float> merge{list_begin.data(), list.data(), id.data(), begin.data(), partner.data(),
                                 kept,              m.touching.data(), to,  halved};
    for (Index i = 0; i < 4; ++i) run_lanes(lanes, [&](const ThreadLane& g) { merge.in_group(i, g); });
    return m;
  };
  auto bits = [](float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  const Merged whole = keep_and_merge(false, 1);
  EXPECT_EQ(whole.touching, (std::vector<std::uint8_t>{1, 1, 1, 1, 0, 1, 1, 0}));
  EXPECT_EQ(bits(whole.tangential[3].y), bits(-s3010.y + 0.0f));  // 10's side of (30, 10): +0, as stored
  for (int lanes : {1, 2, 4, 8}) {
    const Merged half = keep_and_merge(true, lanes);
    EXPECT_EQ(half.touching, whole.touching) << lanes << " lanes";
    for (std::size_t k = 0; k < entries; ++k) {
      EXPECT_EQ(bits(half.spring[k]), bits(whole.spring[k])) << lanes << " lanes, entry " << k;
      EXPECT_EQ(bits(half.tangential[k].x), bits(whole.tangential[k].x)) << lanes << " lanes, entry " << k;
      EXPECT_EQ(bits(half.tangential[k].y), bits(whole.tangential[k].y)) << lanes << " lanes, entry " << k;
      EXPECT_EQ(bits(half.tangential[k].z), bits(whole.tangential[k].z)) << lanes << " lanes, entry " << k;
    }
  }
}

// The old list's entries become the partners' ids, by any number of lanes.
TEST(PairKeep, ListEntriesBecomeIds) {
  const std::vector<ParticleId> id{40, 10, 30, 20, 50};
  const std::vector<ListOffset> begin{0, 3, 3, 5};
  const std::vector<Index> list{1, 2, 4, 0, 3}, want{10, 30, 50, 40, 20};
  for (int lanes : {1, 2, 4, 8}) {
    std::vector<Index> entries = list;
    const ListToIds to_ids{begin.data(), entries.data(), id.data()};
    for (Index i = 0; i < 3; ++i) run_lanes(lanes, [&](const ThreadLane& g) { to_ids.in_group(i, g); });
    EXPECT_EQ(entries, want) << lanes << " lanes";
  }
}

// Arriving rows (slot-major blocks, two arrivals one after the other) leave
// only their pair contacts in the pending table, in row order, each arrival's
// after those pending before it; their surface contacts (a wall, a mesh
// feature) are the surface table's, at most `slots` of them a row.
TEST(PairKeep, ArrivingRowsLeaveTheirPairContactsPending) {
  const ParticleId wall = kWallPartnerBase + 1, mesh = kMeshPartnerBase + 5, other = kWallPartnerBase + 3;
  // Rows (width 3) of the first arrival: {9, wall, 2}, {empty, empty, empty};
  // of the second: {mesh, 5, other wall}, {8, 6, wall}.
  const std::vector<ParticleId> first{9, kNoPartner, wall, kNoPartner, 2, kNoPartner};
  const std::vector<float> first_spring{90, 0, -1, 0, 20, 0};
  const std::vector<ParticleId> second{mesh, 8, 5, 6, other, wall};
  const std::vector<float> second_spring{-2, 80, 50, 60, -4, -3};
  std::vector<ListOffset> begin;
  std::vector<ParticleId> partner;
  std::vector<float> spring;
  pend(begin, partner, spring, first, first_spring, 3);
  pend(begin, partner, spring, second, second_spring, 3);
  EXPECT_EQ(begin, (std::vector<ListOffset>{0, 2, 2, 3, 5}));
  EXPECT_EQ(partner, (std::vector<ParticleId>{9, 2, 5, 8, 6}));
  EXPECT_EQ(spring, (std::vector<float>{90, 20, 50, 80, 60}));
  // The second arrival's surface contacts, each row's in row order: slot
  // and block entry; with one slot a row, the first row's mesh alone fits.
  for (int slots : {1, 4}) {
    const PendingSurfaces surfaces{ArrivingRows{second.data(), 3, 2}, slots, 0, nullptr};
    std::vector<std::vector<ParticleId>> got(2);
    for (Index k = 0; k < 2; ++k)
      surfaces.for_each(k, [&](int s, std::size_t e) {
        EXPECT_EQ(std::size_t(s), got[std::size_t(k)].size());
        got[std::size_t(k)].push_back(second[e]);
      });
    const std::vector<std::vector<ParticleId>> want =
        slots == 1 ? std::vector<std::vector<ParticleId>>{{mesh}, {wall}}
                   : std::vector<std::vector<ParticleId>>{{mesh, other}, {wall}};
    EXPECT_EQ(got, want) << slots << " slots";
  }
}

// A scan past 2^32 - 1 entries would wrap the 32-bit offsets: refused.
TEST(PairKeep, ScanRefusesOffsetsPast32Bits) {
  std::vector<ListOffset> begin{0, 0xF0000000u, 0x20000000u};
  DeviceArray<unsigned char> scratch(Backend::cpu);
  EXPECT_THROW(CpuExec::scan_counts(begin.data(), 2, scratch, "the test's kept table"), std::runtime_error);
}

}  // namespace
}  // namespace gs::test
