#pragma once
// How many rows of a field a GPU's output puts in order at a time
// (ParticleMover's rows_to_host): each chunk is written into the staging
// array, copied to a pinned bounce buffer and from there to the host array.
// Chunks large enough that their launches and waits are negligible beside
// the copies, small enough that output adds little to what the run holds:
// as large as the staging array already is (a build frees it; what the
// exchange or the last output grew it to stays), within [least, 64 MiB],
// where least is 8 MiB, or a 32nd of the field where that is smaller (at
// least 1 MiB): a 4e6 bed's positions (96 MB) go in chunks of 3 MB, 0.75
// bytes per particle beside the run instead of 8 MiB's 2.1.
#include <algorithm>
#include <cstddef>

#include "core/types.hpp"

namespace gs {

inline Index output_chunk_rows(Index n, std::size_t row_bytes, std::size_t staging_bytes) {
  constexpr std::size_t kMiB = std::size_t(1) << 20;
  const std::size_t field_bytes = std::size_t(std::max<Index>(n, 0)) * row_bytes;
  const std::size_t least = std::clamp(field_bytes / 32, kMiB, 8 * kMiB);
  const std::size_t most = std::clamp(staging_bytes, least, 64 * kMiB);
  return Index(std::max<std::size_t>(1, std::min<std::size_t>(std::size_t(n), most / std::max<std::size_t>(row_bytes, 1))));
}

}  // namespace gs
