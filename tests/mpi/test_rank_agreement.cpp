// Agreement on errors and the non-blocking stop reduction between ranks
// (comm/rank_agreement.hpp, Transport::start_min): every rank learns the same
// outcome, whichever rank failed.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "comm/rank_agreement.hpp"

namespace gs::test {
namespace {

Transport& world() {
  static std::unique_ptr<Transport> t = make_mpi_transport();
  return *t;
}

// The message every rank gets when the ranks in `failing` fail with their own
// messages, or "" when throw_if_any_failed returns.
std::string agreed(const std::vector<int>& failing, bool same_message) {
  std::string local;
  for (int r : failing)
    if (r == world().rank()) local = same_message ? "cannot open s.yaml" : "rank's own " + std::to_string(r);
  try {
    throw_if_any_failed(world(), local);
  } catch (const RankFailure& e) {
    return e.what();
  }
  return "";
}

TEST(RankAgreement, NoFailureReturnsOnEveryRank) { EXPECT_EQ(agreed({}, true), ""); }

TEST(RankAgreement, OneFailingRankIsNamedOnEveryRank) {
  const int last = world().size() - 1;
  EXPECT_EQ(agreed({last}, true), "rank " + std::to_string(last) + ": cannot open s.yaml");
  EXPECT_EQ(agreed({0}, false), "rank 0: rank's own 0");
}

TEST(RankAgreement, TheLowestFailingRankSpeaksAndTheOthersAreCounted) {
  std::vector<int> all;
  for (int r = 1; r < world().size(); ++r) all.push_back(r);
  const std::string others = world().size() > 2 ? " (and " + std::to_string(world().size() - 2) + " more rank" +
                                                      (world().size() > 3 ? "s" : "") + " failed)"
                                                : "";
  EXPECT_EQ(agreed(all, false), "rank 1: rank's own 1" + others);
}

TEST(RankAgreement, EveryRankFailingAlikeGivesTheMessageAlone) {
  std::vector<int> all;
  for (int r = 0; r < world().size(); ++r) all.push_back(r);
  EXPECT_EQ(agreed(all, true), "cannot open s.yaml");
}

// Started on every rank, finished later: the minimum over ranks, with other
// collectives in between.
TEST(RankAgreement, NonBlockingMinimum) {
  for (int asking = 0; asking < world().size(); ++asking) {
    world().start_min(world().rank() == asking ? 0 : 1);
    EXPECT_EQ(world().min(world().rank() + 5), 5);
    EXPECT_EQ(world().finish_min(), 0);
  }
  world().start_min(1);
  EXPECT_EQ(world().finish_min(), 1);
  EXPECT_THROW(world().finish_min(), std::logic_error);
}

}  // namespace
}  // namespace gs::test
