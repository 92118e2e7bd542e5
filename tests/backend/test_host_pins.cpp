// Host arrays kept for a backend's copies (backend/host_pins.hpp): resized as
// asked, keeping their memory and values when it suffices and their values
// when it grows (the pages past them faulted in first, on several threads);
// the bounce buffer is kept, grown when asked for more, page-locked, and
// exists on the CUDA backend only, each of its halves holding the copy last
// queued into it; host_copy and touch_pages against plain loops.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "backend/device_array.hpp"
#include "backend/host_pins.hpp"
#include "backend/memory.hpp"
#include "support/support.hpp"

namespace gs {
namespace {

class HostPinsTest : public testing::TestWithParam<Backend> {};

TEST_P(HostPinsTest, ResizesKeepingValuesAndMemory) {
  const Backend b = GetParam();
  HostPins pins;
  std::vector<double> v;
  pins.resize(b, v, 1000);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = 1.0 / double(i + 3);  // no zero bytes
  const double* kept = v.data();
  pins.resize(b, v, 900);  // smaller: the same memory and values
  EXPECT_EQ(v.data(), kept);
  pins.resize(b, v, 3 << 20);  // beyond the capacity (24 MiB): new memory, its pages touched in parallel
  ASSERT_EQ(v.size(), std::size_t(3) << 20);
  for (std::size_t i = 0; i < 900; ++i) ASSERT_EQ(v[i], 1.0 / double(i + 3)) << i;
  for (std::size_t i = 900; i < v.size(); ++i) ASSERT_EQ(v[i], 0.0) << i;
  EXPECT_GE(v.capacity(), v.size());
  EXPECT_EQ(pins.pinned_bytes(), 0u);  // arrays are never pinned
}

TEST_P(HostPinsTest, BounceBufferIsKeptAndPinnedOnAGpuOnly) {
  const Backend b = GetParam();
  const bool gpu = b != Backend::cpu;
  HostPins pins;
  EXPECT_EQ(pins.hold_halves(b, 4 << 20), gpu);  // none on the CPU: its kernels write the host arrays
  EXPECT_EQ(pins.pinned_bytes(), gpu ? std::size_t(8) << 20 : 0u);
  EXPECT_THROW(pins.fill_half(0, nullptr, (std::size_t(4) << 20) + 1), std::logic_error);  // more than a half, or none held
  EXPECT_THROW(pins.fill_half(2, nullptr, 1), std::logic_error);
  EXPECT_EQ(pins.hold_halves(b, 1 << 20), gpu);  // smaller: the same buffer
  EXPECT_EQ(pins.pinned_bytes(), gpu ? std::size_t(8) << 20 : 0u);
  EXPECT_EQ(pins.hold_halves(b, 8 << 20), gpu);  // larger: a new one, pinned anew
  EXPECT_EQ(pins.pinned_bytes(), gpu ? std::size_t(16) << 20 : 0u);
  pins.clear();
  EXPECT_EQ(pins.pinned_bytes(), 0u);
  HostPins never(false);  // copies made once: none
  EXPECT_FALSE(never.hold_halves(b, 4 << 20));
  EXPECT_EQ(never.pinned_bytes(), 0u);
}

// The pipeline of rows_to_host: each half holds the copy last queued into it,
// while the other half is filled, read and filled again.
TEST_P(HostPinsTest, EachHalfHoldsTheCopyLastQueuedIntoIt) {
  const Backend b = GetParam();
  HostPins pins;
  const std::size_t half = (1 << 20) + 24;
  if (!pins.hold_halves(b, half)) GTEST_SKIP() << "no bounce buffer on this backend";
  std::vector<unsigned char> host(4 * half);
  for (std::size_t i = 0; i < host.size(); ++i) host[i] = static_cast<unsigned char>(i * 7 + i / 1021);
  DeviceArray<unsigned char> device(b);
  device.resize(host.size());
  backend_copy_from_host(b, device.data(), host.data(), host.size());
  auto same = [&](const unsigned char* got, std::size_t from, std::size_t bytes) {
    for (std::size_t i = 0; i < bytes; ++i)
      if (got[i] != host[from + i]) return testing::AssertionFailure() << "byte " << i << " of " << from;
    return testing::AssertionSuccess();
  };
  pins.fill_half(0, device.data(), half);
  pins.fill_half(1, device.data() + half, half);
  EXPECT_TRUE(same(pins.filled_half(0), 0, half));
  pins.fill_half(0, device.data() + 2 * half, half - 5);  // a shorter last chunk
  EXPECT_TRUE(same(pins.filled_half(1), half, half));
  pins.fill_half(1, device.data() + 3 * half, half);
  EXPECT_TRUE(same(pins.filled_half(0), 2 * half, half - 5));
  EXPECT_TRUE(same(pins.filled_half(1), 3 * half, half));
}

TEST(HostCopy, CopiesEveryByteOfAnyLengthAndOffset) {
  std::vector<unsigned char> from((5 << 20) + 13), to(from.size() + 16, 0xAB);
  for (std::size_t i = 0; i < from.size(); ++i) from[i] = static_cast<unsigned char>(i * 131 + i / 4099);
  for (std::size_t offset : {0, 3}) {
    for (std::size_t bytes : {std::size_t(0), std::size_t(7), std::size_t(300001), std::size_t(1) << 20, from.size() - offset}) {
      std::fill(to.begin(), to.end(), 0xAB);
      host_copy(to.data() + 1, from.data() + offset, bytes);
      EXPECT_EQ(to[0], 0xAB);
      for (std::size_t i = 0; i < bytes; ++i) ASSERT_EQ(to[1 + i], from[offset + i]) << bytes << " at " << i;
      EXPECT_EQ(to[1 + bytes], 0xAB) << "past the end, " << bytes << " bytes";
    }
  }
}

TEST(TouchPages, WritesOneZeroPerPageInsideTheRangeOnly) {
  const std::size_t page = 4096;  // at least: fewer writes on larger pages
  std::vector<unsigned char> v(40 * page + 100, 0xCD);
  const std::size_t first = 77, bytes = 30 * page + 5;
  touch_pages(v.data() + first, bytes);
  std::size_t zeros = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] == 0xCD) continue;
    ASSERT_EQ(v[i], 0) << i;
    ASSERT_TRUE(i >= first && i < first + bytes) << "outside the range at " << i;
    ++zeros;
  }
  EXPECT_GE(zeros, 1u);
  EXPECT_LE(zeros, bytes / page + 2);
}

INSTANTIATE_TEST_SUITE_P(Backends, HostPinsTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
