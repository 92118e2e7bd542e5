#pragma once
// Host threads that play the lanes of a GPU lane group
// (backend/cuda/lane_group.cuh): a vote waits until every lane of the group
// has voted, as the warp's ballot does, so a kernel's in_group body runs on
// the CPU as a GPU would run it, for any group size.
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace gs {
namespace test {

// What the lanes of one group share: their votes, their shuffled values and a barrier.
class Votes {
 public:
  explicit Votes(int lanes) : votes_(std::size_t(lanes)), values_(std::size_t(lanes)), lanes_(lanes) {}
  // Every lane's vote, once all have voted; each lane calls it equally often.
  unsigned ballot(int rank, bool vote) {
    votes_[std::size_t(rank)] = vote;
    wait();
    unsigned bits = 0;
    for (int r = 0; r < lanes_; ++r) bits |= unsigned(votes_[std::size_t(r)]) << r;
    wait();  // nobody votes again before everyone has read this round
    return bits;
  }
  // Lane `from`'s v, once all lanes have given theirs; each lane calls it equally often.
  template <class T>
  T shuffle(int rank, T v, int from) {
    static_assert(sizeof(T) <= sizeof(std::uint64_t) && std::is_trivially_copyable_v<T>, "one register's worth");
    std::memcpy(&values_[std::size_t(rank)], &v, sizeof v);
    wait();
    T out;
    std::memcpy(&out, &values_[std::size_t(from)], sizeof out);
    wait();
    return out;
  }

 private:
  void wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    const long long round = round_;
    if (++arrived_ == lanes_) {
      arrived_ = 0;
      ++round_;
      all_.notify_all();
    } else {
      all_.wait(lock, [&] { return round_ != round; });
    }
  }
  std::vector<char> votes_;
  std::vector<std::uint64_t> values_;
  int lanes_;
  int arrived_ = 0;
  long long round_ = 0;
  std::mutex mutex_;
  std::condition_variable all_;
};

struct ThreadLane {
  int size;
  int rank;
  Votes* votes;
  bool leader() const { return rank == 0; }
  void sync() const { votes->ballot(rank, false); }  // a barrier: what each lane wrote before, all see
  unsigned ballot(bool vote) const { return votes->ballot(rank, vote); }
  template <class T>
  T shuffle(T v, int from) const {
    return votes->shuffle(rank, v, from);
  }
};

// Runs body(lane) on `lanes` threads, each with its ThreadLane, and joins them.
template <class Body>
void run_lanes(int lanes, const Body& body) {
  Votes votes(lanes);
  std::vector<std::thread> threads;
  for (int rank = 0; rank < lanes; ++rank) threads.emplace_back([&, rank] { body(ThreadLane{lanes, rank, &votes}); });
  for (std::thread& t : threads) t.join();
}

}  // namespace test
}  // namespace gs
