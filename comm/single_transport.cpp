#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "comm/transport.hpp"

namespace gs {
namespace {

class SingleTransport final : public Transport {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  int local_rank() const override { return 0; }
  void exchange(const std::vector<int>& peers, const std::vector<Bytes>&, std::vector<Bytes>& recv) override {
    if (!peers.empty()) throw std::logic_error("a single rank has no peers");
    recv.clear();
  }
  void start_exchange(const std::vector<int>& peers, const std::vector<const unsigned char*>&,
                      const std::vector<std::size_t>&, const std::vector<unsigned char*>&,
                      const std::vector<std::size_t>&) override {
    if (!peers.empty()) throw std::logic_error("a single rank has no peers");
  }
  void finish_exchange() override {}
  void sum(std::vector<std::int64_t>&) override {}
  void sum(std::vector<double>&) override {}
  int min(int value) override { return value; }
  void start_min(int value) override { pending_ = value; }
  int finish_min() override { return pending_; }
  std::vector<Bytes> gather(Bytes local) override {
    std::vector<Bytes> all;
    all.push_back(std::move(local));
    return all;
  }
  Bytes broadcast(const Bytes& data, int) override { return data; }
  [[noreturn]] void abort(int code) override { std::exit(code); }

 private:
  int pending_ = 0;
};

}  // namespace

std::unique_ptr<Transport> make_single_transport() { return std::make_unique<SingleTransport>(); }

}  // namespace gs
