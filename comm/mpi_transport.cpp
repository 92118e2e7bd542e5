#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "comm/transport.hpp"

namespace gs {
namespace {

void check_mpi(int status, const char* call) {
  if (status == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(status, text, &length);
  throw std::runtime_error(std::string("MPI error in ") + call + ": " + std::string(text, std::size_t(length)));
}
#define GS_MPI_CHECK(call) check_mpi((call), #call)

// MPI counts are int: messages are split into chunks below 2^30 bytes.
constexpr std::size_t kChunk = std::size_t(1) << 30;

class MpiTransport final : public Transport {
 public:
  MpiTransport() {
    int initialised = 0;
    GS_MPI_CHECK(MPI_Initialized(&initialised));
    if (!initialised) {
      GS_MPI_CHECK(MPI_Init(nullptr, nullptr));
      std::atexit([] {
        int finalised = 0;
        MPI_Finalized(&finalised);
        if (!finalised) MPI_Finalize();
      });
    }
    GS_MPI_CHECK(MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN));
    GS_MPI_CHECK(MPI_Comm_rank(MPI_COMM_WORLD, &rank_));
    GS_MPI_CHECK(MPI_Comm_size(MPI_COMM_WORLD, &size_));
    MPI_Comm node;
    GS_MPI_CHECK(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node));
    GS_MPI_CHECK(MPI_Comm_rank(node, &local_rank_));
    GS_MPI_CHECK(MPI_Comm_free(&node));
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int local_rank() const override { return local_rank_; }

  // The sizes first, then the data as start_exchange sends it.
  void exchange(const std::vector<int>& peers, const std::vector<Bytes>& send, std::vector<Bytes>& recv) override {
    const std::size_t n = peers.size();
    std::vector<std::uint64_t> send_size(n), recv_size(n);
    for (std::size_t k = 0; k < n; ++k) send_size[k] = send[k].size();
    std::vector<MPI_Request> requests;
    requests.reserve(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
      requests.emplace_back();
      GS_MPI_CHECK(MPI_Irecv(&recv_size[k], 1, MPI_UINT64_T, peers[k], kSizeTag, MPI_COMM_WORLD, &requests.back()));
    }
    for (std::size_t k = 0; k < n; ++k) {
      requests.emplace_back();
      GS_MPI_CHECK(MPI_Isend(&send_size[k], 1, MPI_UINT64_T, peers[k], kSizeTag, MPI_COMM_WORLD, &requests.back()));
    }
    wait_all(requests);
    recv.assign(n, Bytes());
    std::vector<const unsigned char*> from(n);
    std::vector<unsigned char*> to(n);
    std::vector<std::size_t> send_bytes(n), recv_bytes(n);
    for (std::size_t k = 0; k < n; ++k) {
      recv[k].resize(recv_size[k]);
      from[k] = reinterpret_cast<const unsigned char*>(send[k].data());
      to[k] = reinterpret_cast<unsigned char*>(recv[k].data());
      send_bytes[k] = send_size[k];
      recv_bytes[k] = recv_size[k];
    }
    start_exchange(peers, from, send_bytes, to, recv_bytes);
    finish_exchange();
  }

  void start_exchange(const std::vector<int>& peers, const std::vector<const unsigned char*>& send,
                      const std::vector<std::size_t>& send_bytes, const std::vector<unsigned char*>& recv,
                      const std::vector<std::size_t>& recv_bytes) override {
    if (!started_.empty()) throw std::logic_error("an exchange started before the last one finished");
    expected_.clear();  // (left over where the last finish_exchange threw)
    for (std::size_t k = 0; k < peers.size(); ++k)
      for (std::size_t off = 0; off < recv_bytes[k]; off += kChunk) {
        const int count = int(std::min(kChunk, recv_bytes[k] - off));
        started_.emplace_back();
        expected_.push_back({peers[k], count});
        GS_MPI_CHECK(
            MPI_Irecv(recv[k] + off, count, MPI_BYTE, peers[k], kDataTag, MPI_COMM_WORLD, &started_.back()));
      }
    for (std::size_t k = 0; k < peers.size(); ++k)
      for (std::size_t off = 0; off < send_bytes[k]; off += kChunk) {
        started_.emplace_back();
        // MPI 3 takes a const buffer; the cast serves older headers.
        GS_MPI_CHECK(MPI_Isend(const_cast<unsigned char*>(send[k]) + off, int(std::min(kChunk, send_bytes[k] - off)),
                               MPI_BYTE, peers[k], kDataTag, MPI_COMM_WORLD, &started_.back()));
      }
  }
  // A message shorter than agreed would leave stale bytes unnoticed (a longer
  // one fails the receive itself): each receive's count is checked.
  void finish_exchange() override {
    status_.resize(started_.size());
    const int waited = MPI_Waitall(int(started_.size()), started_.data(), status_.data());
    started_.clear();
    GS_MPI_CHECK(waited);
    for (std::size_t r = 0; r < expected_.size(); ++r) {
      int count = 0;
      GS_MPI_CHECK(MPI_Get_count(&status_[r], MPI_BYTE, &count));
      if (count != expected_[r].bytes)
        throw std::runtime_error("a message from rank " + std::to_string(expected_[r].peer) + " has " +
                                 std::to_string(count) + " bytes, " + std::to_string(expected_[r].bytes) +
                                 " expected");
    }
  }

  void sum(std::vector<std::int64_t>& values) override {
    GS_MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_INT64_T, MPI_SUM,
                               MPI_COMM_WORLD));
  }
  void sum(std::vector<double>& values) override {
    GS_MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_SUM,
                               MPI_COMM_WORLD));
  }
  int min(int value) override {
    GS_MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD));
    return value;
  }

  void start_min(int value) override {
    if (pending_ != MPI_REQUEST_NULL) throw std::logic_error("start_min: a reduction is already outstanding");
    pending_value_ = value;
    GS_MPI_CHECK(MPI_Iallreduce(&pending_value_, &pending_result_, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &pending_));
  }
  int finish_min() override {
    if (pending_ == MPI_REQUEST_NULL) throw std::logic_error("finish_min: no reduction was started");
    GS_MPI_CHECK(MPI_Wait(&pending_, MPI_STATUS_IGNORE));
    return pending_result_;
  }

  std::vector<Bytes> gather(Bytes local) override {
    std::vector<Bytes> all;
    if (rank_ != 0) {
      std::vector<Bytes> one;
      one.push_back(std::move(local));
      std::vector<Bytes> none;
      exchange({0}, one, none);
      return all;
    }
    std::vector<int> others;
    for (int r = 1; r < size_; ++r) others.push_back(r);
    std::vector<Bytes> from_others;
    exchange(others, std::vector<Bytes>(others.size()), from_others);
    all.push_back(std::move(local));
    for (Bytes& b : from_others) all.push_back(std::move(b));
    return all;
  }

  Bytes broadcast(const Bytes& data, int root) override {
    std::uint64_t size = data.size();
    GS_MPI_CHECK(MPI_Bcast(&size, 1, MPI_UINT64_T, root, MPI_COMM_WORLD));
    Bytes out = rank_ == root ? data : Bytes(size);
    for (std::size_t off = 0; off < size; off += kChunk)
      GS_MPI_CHECK(MPI_Bcast(out.data() + off, int(std::min<std::size_t>(kChunk, size - off)), MPI_BYTE, root,
                             MPI_COMM_WORLD));
    return out;
  }

  [[noreturn]] void abort(int code) override {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
  }

 private:
  static constexpr int kSizeTag = 17, kDataTag = 18;
  static void wait_all(std::vector<MPI_Request>& requests) {
    GS_MPI_CHECK(MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE));
    requests.clear();
  }
  int rank_ = 0, size_ = 1, local_rank_ = 0;
  // start_exchange's requests until finish_exchange, its receives first,
  // with the sender and size each receive expects.
  struct Expected {
    int peer, bytes;
  };
  // Kept from step to step (the forward runs every step), as is status_.
  std::vector<MPI_Request> started_;
  std::vector<Expected> expected_;
  std::vector<MPI_Status> status_;
  // The outstanding start_min: its buffers must live until MPI_Wait.
  MPI_Request pending_ = MPI_REQUEST_NULL;
  int pending_value_ = 0, pending_result_ = 0;
};

}  // namespace

std::unique_ptr<Transport> make_mpi_transport() { return std::make_unique<MpiTransport>(); }

bool launched_by_mpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
    const char* v = std::getenv(var);
    if (v && std::atoi(v) > 1) return true;
  }
  return false;
}

}  // namespace gs
