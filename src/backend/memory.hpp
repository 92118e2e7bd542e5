#pragma once
#include <cstddef>

#include "backend/backend.hpp"

namespace gs {

// Raw memory of a backend. Every call is checked; failures throw with the
// library's message (an out-of-memory names the size asked for).
void* backend_alloc(Backend b, std::size_t bytes);
void backend_free(Backend b, void* p) noexcept;
void backend_copy_to_host(Backend b, void* host_dst, const void* src, std::size_t bytes);
void backend_copy_from_host(Backend b, void* dst, const void* host_src, std::size_t bytes);
// The same, queued behind the kernels already launched instead of waiting
// for them (CUDA: cudaMemcpyAsync on the default stream; the host's bytes
// are staged before it returns, so they may change at once).
void backend_copy_from_host_queued(Backend b, void* dst, const void* host_src, std::size_t bytes);
void backend_copy(Backend b, void* dst, const void* src, std::size_t bytes);
void backend_zero(Backend b, void* p, std::size_t bytes);
void backend_synchronize(Backend b);
std::size_t backend_peak_bytes(Backend b);  // high-water mark of backend_alloc
void backend_reset_peak(Backend b);         // the high-water mark starts again from what is in use

}  // namespace gs
