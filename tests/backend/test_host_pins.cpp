// Host arrays kept for a backend's copies (backend/host_pins.hpp): resized as
// asked, keeping their memory and values when it suffices and their values
// when it grows (the pages past them faulted in first, on several threads);
// the bounce buffer is kept, grown when asked for more, page-locked, and
// exists on the CUDA backend only; host_copy and touch_pages against plain
// loops.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "backend/host_pins.hpp"
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
  unsigned char* first = pins.bounce(b, 8 << 20);
  EXPECT_EQ(first != nullptr, gpu);  // none on the CPU: its kernels write the host arrays
  EXPECT_EQ(pins.pinned_bytes(), gpu ? std::size_t(8) << 20 : 0u);
  EXPECT_EQ(pins.bounce(b, 1 << 20), first);  // smaller: the same buffer
  EXPECT_EQ(pins.bounce(b, 16 << 20) != nullptr, gpu);  // larger: a new one, pinned anew
  EXPECT_EQ(pins.pinned_bytes(), gpu ? std::size_t(16) << 20 : 0u);
  pins.clear();
  EXPECT_EQ(pins.pinned_bytes(), 0u);
  HostPins never(false);  // copies made once: none
  EXPECT_EQ(never.bounce(b, 8 << 20), nullptr);
  EXPECT_EQ(never.pinned_bytes(), 0u);
}

TEST(HostCopy, CopiesEveryByteOfAnyLengthAndOffset) {
  std::vector<unsigned char> from((5 << 20) + 13), to(from.size() + 16, 0xAB);
  for (std::size_t i = 0; i < from.size(); ++i) from[i] = static_cast<unsigned char>(i * 131 + i / 4099);
  for (std::size_t offset : {0, 3}) {
    for (std::size_t bytes : {std::size_t(0), std::size_t(7), std::size_t(1) << 20, from.size() - offset}) {
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
