#pragma once
// Checkpoints (docs/OUTPUT.md): everything a run needs to continue bit for
// bit, in one HDF5 file. Every value is stored in the type it has in memory
// (positions fp64, radius/mass/inertia fp32, ...), so nothing is rounded.
// A checkpoint is written to a temporary file in the same directory, synced
// and renamed: a crash mid-write leaves the previous checkpoint intact. A
// 64-bit checksum over all data and a `complete` marker written last let
// read_checkpoint refuse a damaged or unfinished file.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/insertion_state.hpp"
#include "core/particle_snapshot.hpp"
#include "walls/wall.hpp"

namespace gs {

// A checkpoint that cannot be used; the message names the file and the cause.
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// 2: history/tangential holds the elastic tangential force [N] of the
// incremental friction law; version 1 held a spring displacement [m], which
// this law cannot continue from.
constexpr int kCheckpointFormatVersion = 2;

struct Checkpoint {
  long long step = 0;
  double time = 0;
  // Every field, force and torque included: the first half kick of velocity
  // Verlet after a restart uses the forces of the step before it.
  ParticleSnapshot particles;
  HostHistory history;  // in `particles` order
  std::vector<Wall> walls;  // with their pose at `time`
  std::uint64_t scene_hash = 0;  // scene_hash() of the scene file's text
  int rank_count = 1;
  int decomposition_axis = 2;               // slab axis: 0 x, 1 y, 2 z; -1: not slabs
  std::vector<double> decomposition_cuts;   // slab bounds along the axis [m]; empty when not slabs
  std::uint64_t random_state = 0;
  std::optional<InsertionState> insertion;  // a run with inlets only (io/checkpoint_insertion.hpp)
};

struct CheckpointExpectations {
  std::optional<std::uint64_t> scene_hash;  // refuse a checkpoint written for another scene
};

// checkpoint_<step, 10 digits>.h5
std::string checkpoint_h5_name(long long step);

// FNV-1a 64 over every value of c, in the order docs/OUTPUT.md gives.
std::uint64_t checkpoint_checksum(const Checkpoint& c);

// Throws std::invalid_argument when an array has the wrong length, and
// h5::H5Error or std::runtime_error when writing fails (the previous file at
// `path`, if any, is then untouched).
void write_checkpoint(const std::string& path, const Checkpoint& c);

// Throws CheckpointError for a missing, truncated, unfinished or damaged file,
// one that is not HDF5 or not a checkpoint, another format version, a
// checksum mismatch, or a scene hash other than the expected one.
Checkpoint read_checkpoint(const std::string& path, const CheckpointExpectations& expect = {});

}  // namespace gs
