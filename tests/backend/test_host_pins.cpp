// Host arrays kept for a backend's copies (backend/host_pins.hpp): resized as
// asked, keeping their memory when it suffices; on the CUDA backend a large
// one is page-locked, pinned anew when it grows, and let go by clear(); on
// the CPU backend nothing is pinned.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "backend/host_pins.hpp"
#include "support/support.hpp"

namespace gs {
namespace {

class HostPinsTest : public testing::TestWithParam<Backend> {};

TEST_P(HostPinsTest, ResizesKeepsMemoryAndPinsLargeArraysOnAGpu) {
  const Backend b = GetParam();
  const bool gpu = b != Backend::cpu;
  std::vector<double> large, small;
  HostPins pins;
  pins.resize(b, large, 1 << 20);  // 8 MiB
  pins.resize(b, small, 100);
  EXPECT_EQ(large.size(), std::size_t(1) << 20);
  EXPECT_EQ(small.size(), 100u);
  EXPECT_EQ(pins.pinned_bytes(), gpu ? large.capacity() * sizeof(double) : 0u);  // small stays pageable
  const double* kept = large.data();
  pins.resize(b, large, 1000);  // smaller: the same memory, still pinned
  EXPECT_EQ(large.data(), kept);
  EXPECT_EQ(pins.pinned_bytes(), gpu ? large.capacity() * sizeof(double) : 0u);
  pins.resize(b, large, 3 << 20);  // beyond the capacity: new memory, pinned anew
  EXPECT_EQ(large.size(), std::size_t(3) << 20);
  EXPECT_EQ(pins.pinned_bytes(), gpu ? large.capacity() * sizeof(double) : 0u);
  pins.clear();
  EXPECT_EQ(pins.pinned_bytes(), 0u);
  HostPins never(false);  // arrays used once: resized only
  never.resize(b, large, 4 << 20);
  EXPECT_EQ(never.pinned_bytes(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, HostPinsTest, testing::ValuesIn(test::test_backends()), test::backend_label);

}  // namespace
}  // namespace gs
