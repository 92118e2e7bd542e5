#pragma once
// A human-readable summary of a grainstorm HDF5 snapshot or checkpoint, for
// `grainstorm info FILE.h5`: kind, time, step, particle count, fields,
// bounding box, walls, scene hash, version; for a checkpoint also the history,
// the decomposition and whether its checksum holds.
#include <string>

namespace gs {

struct H5Description {
  std::string text;      // one "key: value" line per item
  bool damaged = false;  // a checkpoint that read_checkpoint refuses (its cause is in text)
};

// Throws std::runtime_error when the file is missing, not HDF5, or neither a
// grainstorm snapshot nor a checkpoint.
H5Description describe_h5(const std::string& path);

}  // namespace gs
