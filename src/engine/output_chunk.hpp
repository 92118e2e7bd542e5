#pragma once
// How many rows of a field a GPU's output puts in order at a time
// (ParticleMover's rows_to_host): each chunk is written into the staging
// array, copied to a pinned bounce buffer and from there to the host array,
// in two halves of what this allows, so that one half goes to the host while
// the other is filled.
// A 32nd of the field or a byte per row, whichever is less (at least 1 MiB,
// at most 64 MiB), or as much as the staging array already holds where that
// is more (a build frees it; what the exchange or the last output grew it
// to stays), up to 64 MiB. So the output adds at most a byte per particle
// to what the run holds (a 4e6 bed's positions, 96 MB, go in 3 MB, two
// halves of 1.5 MB, 0.75 bytes per particle; a checkpoint's rows of contact
// history in 4 MB). Where the rows are found by a scatter over every
// particle (engine/row_order.hpp), each half is a pass over the ids: at most
// 64 passes a field for rows of up to 32 bytes (an fp64 vector: 24), and for
// wider rows 8 bytes of ids read per byte copied, in device memory, which
// is some hundred times faster than the copies to the host.
#include <algorithm>
#include <cstddef>

#include "core/types.hpp"

namespace gs {

inline Index output_chunk_rows(Index n, std::size_t row_bytes, std::size_t staging_bytes) {
  constexpr std::size_t kMiB = std::size_t(1) << 20;
  const std::size_t rows = std::size_t(std::max<Index>(n, 0));
  const std::size_t field_bytes = rows * row_bytes;
  const std::size_t least = std::clamp(std::min(field_bytes / 32, rows), kMiB, 64 * kMiB);
  const std::size_t most = std::clamp(staging_bytes, least, 64 * kMiB);
  return Index(std::max<std::size_t>(1, std::min(rows, most / std::max<std::size_t>(row_bytes, 1))));
}

}  // namespace gs
