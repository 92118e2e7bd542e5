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

// A phase that throws on one rank stops every rank with its message; one
// whose exception says nothing still counts as a failure.
TEST(RankAgreement, OnEveryRankStopsAllWhenOnePhaseThrows) {
  const int last = world().size() - 1;
  const auto fails_on = [](int rank, const char* what) {
    return [=] {
      if (world().rank() == rank) throw std::runtime_error(what);
    };
  };
  EXPECT_NO_THROW(on_every_rank(world(), [] {}));
  try {
    on_every_rank(world(), fails_on(last, "cannot read s.yaml"));
    ADD_FAILURE() << "no rank threw";
  } catch (const RankFailure& e) {
    EXPECT_EQ(std::string(e.what()), world().size() == 1 ? "cannot read s.yaml"
                                                          : "rank " + std::to_string(last) + ": cannot read s.yaml");
  }
  EXPECT_THROW(on_every_rank(world(), fails_on(last, "")), RankFailure);
}

// Only rank 0 writes, and its failure, even a silent one, stops every rank.
TEST(RankAgreement, WrittenByRank0RunsOnRank0AndSharesItsFailure) {
  int writes = 0;
  written_by_rank_0(world(), [&] { ++writes; });
  EXPECT_EQ(writes, world().rank() == 0 ? 1 : 0);
  EXPECT_THROW(written_by_rank_0(world(), [] { throw std::runtime_error("disk full"); }), RankFailure);
  EXPECT_THROW(written_by_rank_0(world(), [] { throw std::runtime_error(""); }), RankFailure);
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
