// The kept table of a list rebuild (engine/pair_keep.hpp), against contacts
// listed by hand: a particle's touching contacts come out of its carried row
// in ascending partner id, and out of a pending row (as it arrived, in any
// order, with surface contacts and empty entries) sorted by partner id with
// the surface contacts and empties left out; the new list's entries then
// find the springs of their partner, and zero where it did not touch.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "backend/cpu/cpu_exec.hpp"
#include "engine/pair_keep.hpp"

namespace gs::test {
namespace {

// Three owned particles: 0 from carried row 1, 1 from pending row 0, 2 new.
// Carried row 1 lists partners 3, 5, 8, 9 (5 and 9 not touching); the pending
// row (width 5) holds partner 7, a wall, 4, an empty entry and partner 6.
struct Detached {
  std::vector<Index> origin{1, kPendingBase + 0};  // particle 2 has none (beyond)
  std::vector<ListOffset> carried_begin{0, 2, 6};
  std::vector<Index> carried_partner{11, 12, 3, 5, 8, 9};
  std::vector<std::uint8_t> carried_touching{1, 1, 1, 0, 1, 0};
  std::vector<float> carried_spring{-1, -2, 30, 0, 80, 0};
  std::vector<ParticleId> pending_partner{7, kWallPartnerBase + 2, 4, kNoPartner, 6};
  std::vector<float> pending_spring{70, 99, 40, 0, 60};
  DetachedContacts contacts() const {
    const DetachedTables tables{origin.data(),          Index(origin.size()),    carried_begin.data(),
                                carried_partner.data(), carried_touching.data(), pending_partner.data()};
    return {tables, 5};
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

TEST(PairKeep, TouchingContactsInAscendingPartnerId) {
  const Detached d;
  const std::vector<ListOffset> begin = counted(d, 3);
  EXPECT_EQ(begin, (std::vector<ListOffset>{0, 2, 5, 5}));  // 2 carried, 3 pending, none
  std::vector<ParticleId> partner(5);
  std::vector<float> spring(5);
  CpuExec::parallel_for(3, KeepPartners{d.contacts(), begin.data(), partner.data()});
  CpuExec::parallel_for(
      3, KeepField<float>{d.contacts(), begin.data(), d.carried_spring.data(), d.pending_spring.data(), spring.data()});
  EXPECT_EQ(partner, (std::vector<ParticleId>{3, 8, 4, 6, 7}));
  EXPECT_EQ(spring, (std::vector<float>{30, 80, 40, 60, 70}));
}

// The new list of particle 0: partners 2, 3, 5, 8 (5 was listed, not
// touching; 2 is new); of particle 1: 4, 7 (6 left its reach); particle 2: 3.
TEST(PairKeep, NewEntriesFindTheirPartnersSprings) {
  const std::vector<ParticleId> id{0, 1, 2, 3, 4, 5, 6, 7, 8};  // store index = id here
  const std::vector<ListOffset> list_begin{0, 4, 6, 7};
  const std::vector<Index> list{2, 3, 5, 8, 4, 7, 3};
  const std::vector<ListOffset> kept_begin{0, 2, 5, 5};
  const std::vector<ParticleId> kept_partner{3, 8, 4, 6, 7};
  const std::vector<float> kept_spring{30, 80, 40, 60, 70};
  const KeptSources sources{list_begin.data(), list.data(), id.data(), kept_begin.data(), kept_partner.data()};
  std::vector<float> spring(7, -7);
  std::vector<std::uint8_t> touching(7, 7);
  CpuExec::parallel_for(3, MergeKeptField<float>{sources, kept_spring.data(), spring.data()});
  CpuExec::parallel_for(3, MergeKeptTouching{sources, touching.data()});
  EXPECT_EQ(spring, (std::vector<float>{0, 30, 0, 80, 40, 70, 0}));
  EXPECT_EQ(touching, (std::vector<std::uint8_t>{0, 1, 0, 1, 1, 1, 0}));
}

// A scan past 2^32 - 1 entries would wrap the 32-bit offsets: refused.
TEST(PairKeep, ScanRefusesOffsetsPast32Bits) {
  std::vector<ListOffset> begin{0, 0xF0000000u, 0x20000000u};
  DeviceArray<unsigned char> scratch(Backend::cpu);
  EXPECT_THROW(CpuExec::scan_counts(begin.data(), 2, scratch, "the test's kept table"), std::runtime_error);
}

}  // namespace
}  // namespace gs::test
