#pragma once
// How ranks talk: byte buffers between neighbours, small collectives. Two
// implementations: one rank (no MPI), and MPI over host buffers (CPU ranks,
// and GPU ranks staging through the host).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gs {

using Bytes = std::vector<char>;

class Transport {
 public:
  virtual ~Transport() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Rank among the ranks of this host (selects the GPU).
  virtual int local_rank() const = 0;

  // Sends send[k] to peers[k] and receives recv[k] from peers[k]. Every rank
  // lists the same pairs (a in b's peers iff b in a's). Collective over peers.
  virtual void exchange(const std::vector<int>& peers, const std::vector<Bytes>& send, std::vector<Bytes>& recv) = 0;
  // The same for messages whose sizes both sides know already (the halo's
  // forward between rebuilds), without the size handshake and into the
  // caller's buffers, split so that the caller can work while they travel:
  // start_exchange posts the sends of send_bytes[k] bytes at send[k] to
  // peers[k] and the receives of recv_bytes[k] bytes into recv[k] (host
  // memory left untouched until finish_exchange) and returns at once;
  // finish_exchange returns when every message has arrived and every send
  // buffer may be reused. At most one is outstanding; nothing else may use
  // the transport between the two. Zero-byte entries are skipped.
  virtual void start_exchange(const std::vector<int>& peers, const std::vector<const unsigned char*>& send,
                              const std::vector<std::size_t>& send_bytes, const std::vector<unsigned char*>& recv,
                              const std::vector<std::size_t>& recv_bytes) = 0;
  virtual void finish_exchange() = 0;
  virtual void sum(std::vector<std::int64_t>& values) = 0;  // all-reduce, in place
  // All-reduce, in place. The grouping of the additions is MPI's: the result
  // is not bitwise independent of the rank count (use it for reported totals).
  virtual void sum(std::vector<double>& values) = 0;
  virtual int min(int value) = 0;                           // all-reduce
  // Non-blocking all-reduce (minimum) of one value, for a flag read every
  // step without waiting on the slowest rank: start_min posts it and returns
  // at once, finish_min waits for it and returns the result. Collective: every
  // rank starts and finishes the same reductions in the same order; at most one
  // is outstanding.
  virtual void start_min(int value) = 0;
  virtual int finish_min() = 0;
  // Every rank's bytes in rank order on rank 0; empty elsewhere.
  virtual std::vector<Bytes> gather(Bytes local) = 0;
  virtual Bytes broadcast(const Bytes& data, int root) = 0;
  // Ends every rank at once (a failure no collective can report).
  [[noreturn]] virtual void abort(int code) = 0;
};

// One rank, no MPI.
std::unique_ptr<Transport> make_single_transport();
// MPI_COMM_WORLD; initialises MPI on first use and finalises it at exit.
std::unique_ptr<Transport> make_mpi_transport();
// True when this process was started by mpirun/mpiexec/srun with more than one rank.
bool launched_by_mpi();

}  // namespace gs
