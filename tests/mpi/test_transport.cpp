// Messages of sizes both sides know (Transport::start_exchange and
// finish_exchange, the halo's forward between rebuilds): each rank swaps
// bytes with the ranks next to it in a ring, whose sizes and contents both
// sides compute independently; a message shorter than agreed is refused on
// the rank that receives it, naming the sender.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "comm/transport.hpp"

namespace gs::test {
namespace {

Transport& world() {
  static std::unique_ptr<Transport> t = make_mpi_transport();
  return *t;
}

// The ring's neighbours of this rank, ascending, without repeats.
std::vector<int> ring_peers() {
  const int n = world().size(), r = world().rank();
  std::vector<int> peers;
  for (int q : {(r + n - 1) % n, (r + 1) % n})
    if (q != r && (peers.empty() || peers[0] != q)) peers.push_back(q);
  std::sort(peers.begin(), peers.end());
  return peers;
}

// What `from` sends `to` in round `round`: a size and bytes of its own.
std::size_t agreed_bytes(int from, int to, int round) {
  return std::size_t(1000 + 7919 * from + 104 * to + round * 3);
}
unsigned char agreed_byte(int from, int to, int round, std::size_t k) {
  return static_cast<unsigned char>((k * 31 + std::size_t(from) * 7 + std::size_t(to) * 13 + std::size_t(round)) & 0xff);
}

TEST(Transport, MessagesOfAgreedSizesArriveWhole) {
  const std::vector<int> peers = ring_peers();
  const int me = world().rank();
  std::vector<std::vector<unsigned char>> out(peers.size()), in(peers.size());
  for (int round = 0; round < 3; ++round) {  // buffers reused, sizes changing
    std::vector<const unsigned char*> send;
    std::vector<unsigned char*> recv;
    std::vector<std::size_t> send_bytes, recv_bytes;
    for (std::size_t p = 0; p < peers.size(); ++p) {
      out[p].resize(agreed_bytes(me, peers[p], round));
      for (std::size_t k = 0; k < out[p].size(); ++k) out[p][k] = agreed_byte(me, peers[p], round, k);
      in[p].assign(agreed_bytes(peers[p], me, round), 0);
      send.push_back(out[p].data());
      send_bytes.push_back(out[p].size());
      recv.push_back(in[p].data());
      recv_bytes.push_back(in[p].size());
    }
    world().start_exchange(peers, send, send_bytes, recv, recv_bytes);
    EXPECT_THROW(world().start_exchange(peers, send, send_bytes, recv, recv_bytes), std::logic_error);
    world().finish_exchange();
    for (std::size_t p = 0; p < peers.size(); ++p)
      for (std::size_t k = 0; k < in[p].size(); ++k)
        ASSERT_EQ(in[p][k], agreed_byte(peers[p], me, round, k)) << "from rank " << peers[p] << ", byte " << k;
  }
}

TEST(Transport, AShortMessageIsRefusedNamingItsSender) {
  // Rank 0 sends rank 1 one byte fewer than rank 1 expects; every other
  // message is whole.
  const std::vector<int> peers = ring_peers();
  const int me = world().rank();
  std::vector<std::vector<unsigned char>> out(peers.size()), in(peers.size());
  std::vector<const unsigned char*> send;
  std::vector<unsigned char*> recv;
  std::vector<std::size_t> send_bytes, recv_bytes;
  for (std::size_t p = 0; p < peers.size(); ++p) {
    out[p].assign(agreed_bytes(me, peers[p], 0) - (me == 0 && peers[p] == 1 ? 1 : 0), 1);
    in[p].assign(agreed_bytes(peers[p], me, 0), 0);
    send.push_back(out[p].data());
    send_bytes.push_back(out[p].size());
    recv.push_back(in[p].data());
    recv_bytes.push_back(in[p].size());
  }
  world().start_exchange(peers, send, send_bytes, recv, recv_bytes);
  if (me != 1) {
    EXPECT_NO_THROW(world().finish_exchange());
    return;
  }
  try {
    world().finish_exchange();
    ADD_FAILURE() << "a short message was accepted";
  } catch (const std::runtime_error& e) {
    const std::string expected = "a message from rank 0 has " + std::to_string(agreed_bytes(0, 1, 0) - 1) + " bytes, " +
                                 std::to_string(agreed_bytes(0, 1, 0)) + " expected";
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

}  // namespace
}  // namespace gs::test
