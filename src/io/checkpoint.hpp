#pragma once
// Checkpoints (docs/OUTPUT.md): everything a run needs to continue bit for
// bit, in one HDF5 file. Every value is stored in the type it has in memory
// (positions fp64, radius/mass/inertia fp32, ...), so nothing is rounded.
// A checkpoint is written to a temporary file in the same directory, synced
// and renamed: a crash mid-write leaves the previous checkpoint intact. A
// 64-bit checksum over all data and a `complete` marker written last let
// read_checkpoint refuse a damaged or unfinished file.
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/insertion_state.hpp"
#include "core/particle_snapshot.hpp"
#include "io/fnv1a.hpp"
#include "walls/wall.hpp"

namespace gs {

// A checkpoint that cannot be used; the message names the file and the cause.
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// 2: history/tangential holds the elastic tangential force [N] of the
// incremental friction law; version 1 held a spring displacement [m], which
// this law cannot continue from.
// 3: a checksum per block of particles of every array (checksums/blocks), so
// that a rank verifies the blocks it reads; the file's `checksum` covers the
// header values, that table, the walls and the rest. Version 2 is refused.
constexpr int kCheckpointFormatVersion = 3;

// Particles per checksummed block of a checkpoint's arrays (and per block a
// reader reads).
constexpr std::size_t kChecksumBlockRows = std::size_t(1) << 20;

struct Checkpoint {
  long long step = 0;
  double time = 0;
  // Every field, force and torque included: the first half kick of velocity
  // Verlet after a restart uses the forces of the step before it.
  ParticleSnapshot particles;
  HostHistory history;  // in `particles` order
  std::vector<Wall> walls;  // with their pose at `time`
  std::uint64_t scene_hash = 0;  // scene_hash() of the scene file's text
  // That text itself (dataset `scene_text`), so that a restart with an edited
  // scene can say what the edit changed; empty in checkpoints written before
  // 2026-12-05, which did not store it.
  std::string scene_text;
  int rank_count = 1;
  int decomposition_axis = 2;               // slab axis: 0 x, 1 y, 2 z; -1: not slabs
  std::vector<double> decomposition_cuts;   // slab bounds along the axis [m]; empty when not slabs
  std::uint64_t random_state = 0;
  std::optional<InsertionState> insertion;  // a run with inlets only (io/checkpoint_insertion.hpp)
  std::size_t checksum_block_rows = kChecksumBlockRows;  // as written, or read from the file
};

struct CheckpointExpectations {
  std::optional<std::uint64_t> scene_hash;  // refuse a checkpoint written for another scene
};

// checkpoint_<step, 10 digits>.h5
std::string checkpoint_h5_name(long long step);

// FNV-1a 64 of each block of checksum_block_rows particles of each array
// c stores per particle (particle fields, force, torque, history; those a
// run keeps), array by array in the order docs/OUTPUT.md gives.
std::vector<std::uint64_t> checkpoint_block_checksums(const Checkpoint& c);
// FNV-1a 64 over c's header values, the block size, the block checksums, the
// walls, the cuts and the insertion state: the file's `checksum`.
std::uint64_t checkpoint_checksum(const Checkpoint& c, const std::vector<std::uint64_t>& block_checksums);
std::uint64_t checkpoint_checksum(const Checkpoint& c);

// The checksum's values before the arrays: c's step, times, hashes and
// decomposition, `particles` (N), the history slots, `history_rows` (the row
// count of each history field the file stores, in field order) and the wall
// and cut counts. Shared by checkpoint_checksum and the block-wise reader.
void add_checksum_header(Fnv1a64& sum, const Checkpoint& c, std::uint64_t particles,
                         const std::vector<std::uint64_t>& history_rows);
// The checksum's values after the block checksums: the walls, the cuts, the
// insertion state and the scene text (when stored). Shared as above.
void add_checksum_trailer(Fnv1a64& sum, const Checkpoint& c);

// Throws std::invalid_argument when an array has the wrong length, and
// h5::H5Error or std::runtime_error when writing fails (the previous file at
// `path`, if any, is then untouched).
void write_checkpoint(const std::string& path, const Checkpoint& c);

// Throws CheckpointError for a missing, truncated, unfinished or damaged file,
// one that is not HDF5 or not a checkpoint, another format version, a
// checksum mismatch, or a scene hash other than the expected one.
//
// The arrays are read a block of particles at a time and the checksum is
// computed over every block; `keep`, when given, selects by stored position
// the particles the result holds (with their history rows, in file order), so
// a rank of a restart holds its own particles only. Everything else (step,
// time, walls, the decomposition) is read whole.
Checkpoint read_checkpoint(const std::string& path, const CheckpointExpectations& expect = {},
                           const std::function<bool(const Vec3d&)>& keep = {});

// Calls use(first index, positions) for blocks of the stored positions of the
// checkpoint's particles [first, last) (clamped to its count), unverified: the
// split of a restart reads them before read_checkpoint verifies the file.
// CheckpointError when the file cannot be read.
void for_each_checkpoint_position_block(const std::string& path, std::size_t first, std::size_t last,
                                        const std::function<void(std::size_t, const std::vector<Vec3d>&)>& use);

// The particle count a checkpoint holds (CheckpointError when it cannot be read).
std::size_t checkpoint_particle_count(const std::string& path);

}  // namespace gs
