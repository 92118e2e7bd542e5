#pragma once
#include <cstddef>

#include "backend/backend.hpp"

namespace gs {

// Raw memory of a backend. Every call is checked; failures throw with the
// library's message (an out-of-memory names the size asked for).
//
// A GPU's memory comes from the device's stream-ordered pool (cudaMallocAsync
// and cudaFreeAsync on the default stream, where every kernel and copy of
// grainstorm runs), told to keep the pages it is given back: cudaFree waits
// for the device and returns its pages to the driver, which left the GPU idle
// for most of 0.85 ms at each list build of a 4e6 bed (docs/PERFORMANCE.md,
// "The device's memory pool"). A request the pool cannot serve is made again
// once the device is idle and the pool has released every free page, so what
// fits is what fits with cudaMalloc. GRAINSTORM_CUDA_POOL=0 allocates with
// cudaMalloc and cudaFree instead (1 or unset: the pool; anything else throws
// std::invalid_argument naming the variable).
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
// Whether a GPU allocates from the pool: GRAINSTORM_CUDA_POOL, read once
// (select_cuda_device reads it first); parse_cuda_pool_setting reads a value.
bool cuda_pool_setting();
bool parse_cuda_pool_setting(const char* value);
// The high-water mark of what the backend held from the system: a GPU pool's
// reserved bytes (the allocations' peak plus the pool's rounding to its
// pages), else backend_peak_bytes.
std::size_t backend_reserved_peak_bytes(Backend b);

}  // namespace gs
