// GRAINSTORM_GPU_WAIT (backend/backend.hpp): how a run's host thread waits for
// its GPU. Unset, the CUDA runtime chooses; spin, yield and block are taken;
// anything else is refused with a message naming the variable. On the CUDA
// backend the device then carries the chosen flag.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "backend/backend.hpp"

#ifdef GS_HAVE_CUDA
#include <cuda_runtime.h>
#endif

namespace gs {
namespace {

// Sets the variable for one test and restores it after.
class GpuWaitTest : public testing::Test {
 protected:
  void SetUp() override {
    const char* v = std::getenv("GRAINSTORM_GPU_WAIT");
    had_ = v != nullptr;
    if (had_) old_ = v;
  }
  void TearDown() override {
    if (had_) setenv("GRAINSTORM_GPU_WAIT", old_.c_str(), 1);
    else unsetenv("GRAINSTORM_GPU_WAIT");
  }
  bool had_ = false;
  std::string old_;
};

TEST_F(GpuWaitTest, UnsetLeavesTheChoiceToTheRuntime) {
  unsetenv("GRAINSTORM_GPU_WAIT");
  EXPECT_EQ(gpu_wait_flags(), 0u);
}

TEST_F(GpuWaitTest, UnknownModeIsRefusedByName) {
  setenv("GRAINSTORM_GPU_WAIT", "sleep", 1);
  try {
    gpu_wait_flags();
    FAIL() << "an unknown mode was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("GRAINSTORM_GPU_WAIT must be spin, yield or block, got 'sleep'"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(GpuWaitTest, KnownModesAreTaken) {
  for (const char* mode : {"spin", "yield", "block"}) {
    setenv("GRAINSTORM_GPU_WAIT", mode, 1);
    EXPECT_NO_THROW(gpu_wait_flags()) << mode;
  }
#ifdef GS_HAVE_CUDA
  setenv("GRAINSTORM_GPU_WAIT", "block", 1);
  EXPECT_EQ(gpu_wait_flags(), unsigned(cudaDeviceScheduleBlockingSync));
  if (cuda_device_available()) {
    select_cuda_device(0);
    unsigned flags = 0;
    ASSERT_EQ(cudaGetDeviceFlags(&flags), cudaSuccess);
    EXPECT_EQ(flags & cudaDeviceScheduleMask, unsigned(cudaDeviceScheduleBlockingSync));
  }
#endif
}

}  // namespace
}  // namespace gs
