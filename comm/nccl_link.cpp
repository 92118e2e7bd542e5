#define GS_CUDA_HOST_CODE  // GS_CUDA_CHECK in host code
#include "comm/device_link.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#ifdef GS_HAVE_NCCL
#include <cuda_runtime.h>
#include <nccl.h>

#include "backend/check.hpp"
#endif

namespace gs {

#ifdef GS_HAVE_NCCL
namespace {

#define GS_NCCL_CHECK(call)                                                                   \
  do {                                                                                        \
    const ncclResult_t gs_status_ = (call);                                                   \
    if (gs_status_ != ncclSuccess)                                                            \
      ::gs::throw_external_error("NCCL", #call, __FILE__, __LINE__, ncclGetErrorString(gs_status_)); \
  } while (0)

class NcclLink final : public DeviceLink {
 public:
  explicit NcclLink(Transport& t) {
    ncclUniqueId id{};
    if (t.rank() == 0) GS_NCCL_CHECK(ncclGetUniqueId(&id));
    const Bytes mine(reinterpret_cast<const char*>(&id), reinterpret_cast<const char*>(&id) + sizeof(id));
    const Bytes root = t.broadcast(mine, 0);
    if (root.size() != sizeof(id)) throw std::runtime_error("NCCL: the unique id did not arrive whole");
    std::copy(root.begin(), root.end(), reinterpret_cast<char*>(&id));
    GS_NCCL_CHECK(ncclCommInitRank(&comm_, t.size(), id, t.rank()));
  }
  ~NcclLink() override { ncclCommDestroy(comm_); }
  NcclLink(const NcclLink&) = delete;
  NcclLink& operator=(const NcclLink&) = delete;

  // On the legacy default stream, where the pack kernels ran: the sends
  // start after them, and the unpack kernels start after the receives.
  void exchange(const std::vector<int>& peers, const std::vector<const unsigned char*>& send,
                const std::vector<std::size_t>& send_bytes, const std::vector<unsigned char*>& recv,
                const std::vector<std::size_t>& recv_bytes) override {
    const cudaStream_t stream = cudaStreamLegacy;
    GS_NCCL_CHECK(ncclGroupStart());
    for (std::size_t p = 0; p < peers.size(); ++p) {
      if (send_bytes[p] > 0) GS_NCCL_CHECK(ncclSend(send[p], send_bytes[p], ncclUint8, peers[p], comm_, stream));
      if (recv_bytes[p] > 0) GS_NCCL_CHECK(ncclRecv(recv[p], recv_bytes[p], ncclUint8, peers[p], comm_, stream));
    }
    GS_NCCL_CHECK(ncclGroupEnd());
    GS_CUDA_CHECK(cudaStreamSynchronize(stream));
  }

 private:
  ncclComm_t comm_ = nullptr;
};

}  // namespace

bool nccl_available() { return true; }
std::unique_ptr<DeviceLink> make_nccl_link(Transport& transport) { return std::make_unique<NcclLink>(transport); }

#else

bool nccl_available() { return false; }
std::unique_ptr<DeviceLink> make_nccl_link(Transport&) {
  throw std::runtime_error("the NCCL exchange was asked for, but this grainstorm was built without NCCL");
}

#endif

}  // namespace gs
