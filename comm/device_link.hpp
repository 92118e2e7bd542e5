#pragma once
// Moves packed particle messages between the backend (GPU) buffers of
// neighbouring ranks directly, NCCL over NVLink or the network, so that GPU
// ranks do not stage them through the host. The messages' small headers
// still travel over the Transport, which also bootstraps the link.
#include <cstddef>
#include <memory>
#include <vector>

#include "comm/transport.hpp"

namespace gs {

class DeviceLink {
 public:
  virtual ~DeviceLink() = default;
  // Sends send_bytes[k] bytes at send[k] to peers[k] and receives
  // recv_bytes[k] bytes from peers[k] into recv[k] (device pointers), all at
  // once; zero-byte entries are skipped, and each pair of ranks agrees on
  // the sizes beforehand. Returns when the received bytes are in place.
  virtual void exchange(const std::vector<int>& peers, const std::vector<const unsigned char*>& send,
                        const std::vector<std::size_t>& send_bytes, const std::vector<unsigned char*>& recv,
                        const std::vector<std::size_t>& recv_bytes) = 0;
};

// True when this grainstorm was built with NCCL.
bool nccl_available();
// An NCCL communicator over all the transport's ranks, each on its current
// CUDA device. Collective; throws when NCCL is not built in or fails.
std::unique_ptr<DeviceLink> make_nccl_link(Transport& transport);

}  // namespace gs
