// The writer's thread: jobs run one at a time in the order given (also when
// queued with then()), a job's error comes back from wait() once, and the
// destructor waits for the jobs in hand (their files are complete when the
// owner is gone).
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "io/background_writer.hpp"

namespace gs {
namespace {

TEST(BackgroundWriter, RunsJobsInOrderAndReportsTheirErrorOnce) {
  BackgroundWriter writer;
  std::vector<int> done;
  writer.start([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    done.push_back(1);
  });
  EXPECT_EQ(writer.wait(), "");
  EXPECT_EQ(done, std::vector<int>{1});  // wait() returns once the job is done
  writer.start([] { throw std::runtime_error("cannot create /full/disk/particles_0000000100.h5"); });
  EXPECT_EQ(writer.wait(), "cannot create /full/disk/particles_0000000100.h5");
  EXPECT_EQ(writer.wait(), "");  // reported once
  writer.start([&] { done.push_back(2); });
  EXPECT_EQ(writer.wait(), "");
  EXPECT_EQ(done, (std::vector<int>{1, 2}));
}

TEST(BackgroundWriter, RefusesASecondJobWhileOneIsInHand) {
  BackgroundWriter writer;
  writer.start([] { std::this_thread::sleep_for(std::chrono::milliseconds(20)); });
  EXPECT_THROW(writer.start([] {}), std::logic_error);
  EXPECT_EQ(writer.wait(), "");
}

// then(): the job follows the one in hand without a wait by the caller; both
// run, in order, and wait() returns both errors.
TEST(BackgroundWriter, ThenRunsAfterTheJobInHand) {
  BackgroundWriter writer;
  std::vector<int> done;
  writer.start([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    done.push_back(1);
    throw std::runtime_error("snapshot failed");
  });
  writer.then([&] {
    done.push_back(2);
    throw std::runtime_error("checkpoint failed");
  });
  writer.then([&] { done.push_back(3); });
  EXPECT_EQ(writer.wait(), "snapshot failed; checkpoint failed");
  EXPECT_EQ(done, (std::vector<int>{1, 2, 3}));
  writer.then([&] { done.push_back(4); });  // none in hand: at once
  EXPECT_EQ(writer.wait(), "");
  EXPECT_EQ(done, (std::vector<int>{1, 2, 3, 4}));
}

TEST(BackgroundWriter, DestructorWaitsForTheJob) {
  bool finished = false;
  {
    BackgroundWriter writer;
    writer.start([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      finished = true;
    });
  }
  EXPECT_TRUE(finished);
}

}  // namespace
}  // namespace gs
