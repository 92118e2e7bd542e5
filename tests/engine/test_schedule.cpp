// Steps of periodic events (the mixing analysis once per revolution): the
// k-th falls at the step nearest start + k every, so a run whose duration is
// start + 32 revolutions evaluates its 32nd revolution at its last step.
// Checked against the times computed one by one, for step sizes that do not
// divide the period.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "engine/schedule.hpp"

namespace gs {
namespace {

TEST(Schedule, LastRevolutionOfTheSoftMixerRunIsItsLastStep) {
  // About case_a_soft: 8.177e-5 s steps, settle 1 s, 32 revolutions of 2 s.
  const double dt = 8.1768e-05;
  const Schedule s{1.0, 2.0, dt};
  const long long last = std::llround(65.0 / dt);
  EXPECT_TRUE(s.due(last));
  EXPECT_EQ(s.step_of(32), last);
  // The rule it replaces (first + k rounded periods) never reaches that step.
  const long long first = std::llround(1.0 / dt), period = std::llround(2.0 / dt);
  EXPECT_NE((last - first) % period, 0) << "the example no longer shows the drift";
}

TEST(Schedule, DueStepsAreTheNearestStepsToEachTime) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const double dt = 1e-5 * (1 + u(rng)), every = dt * (3 + 500 * u(rng)), start = every * 3 * u(rng);
    const Schedule s{start, every, dt};
    const long long horizon = std::llround((start + 20 * every) / dt);
    std::set<long long> expected;
    for (int k = 0; k <= 20; ++k) expected.insert(std::llround((start + k * every) / dt));
    std::set<long long> due;
    for (long long step = 0; step <= horizon; ++step)
      if (s.due(step)) due.insert(step);
    ASSERT_EQ(due, expected) << "dt " << dt << " every " << every << " start " << start;
    // next_after walks the same steps.
    std::set<long long> walked;
    if (s.due(0)) walked.insert(0);
    for (long long step = 0; (step = s.next_after(step)) <= horizon;) walked.insert(step);
    EXPECT_EQ(walked, expected);
  }
  EXPECT_FALSE(Schedule{}.due(0)) << "no period: never due";
}

}  // namespace
}  // namespace gs
