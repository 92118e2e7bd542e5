// read_checkpoint: every way a checkpoint can be unusable ends in a
// CheckpointError that names the file and the cause.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <type_traits>

#include "io/checkpoint.hpp"
#include "io/checkpoint_insertion.hpp"
#include "io/fnv1a.hpp"
#include "io/h5_io.hpp"
#include "io/h5_walls.hpp"

namespace gs {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw CheckpointError("checkpoint " + path + " refused: " + why);
}

h5::File open_checked(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) refuse(path, "a directory, not a checkpoint file");
  if (!std::filesystem::is_regular_file(path, ec)) refuse(path, "no such file");
  h5::silence_library_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0)
    refuse(path, "not an HDF5 file (no HDF5 signature in its " +
                     std::to_string(std::filesystem::file_size(path, ec)) + " bytes)");
  try {
    return h5::File::open_read_only(path);
  } catch (const h5::H5Error& e) {
    refuse(path, std::string("the file is truncated or damaged and cannot be opened [") + e.what() + "]");
  }
}

void check_header(const h5::File& f) {
  const std::string& path = f.path();
  if (!h5::has_attribute(f, "/", "kind")) refuse(path, "not a grainstorm checkpoint (no 'kind' attribute)");
  const std::string kind = h5::read_string_attribute(f, "/", "kind");
  if (kind != "grainstorm checkpoint") refuse(path, "not a grainstorm checkpoint (kind '" + kind + "')");
  const auto version = h5::read_attribute<std::int32_t>(f, "/", "format_version");
  if (version == 1)
    refuse(path, "format version 1, but this grainstorm reads version " + std::to_string(kCheckpointFormatVersion) +
                     ": version 1 stored the tangential springs as displacements [m], this friction law carries "
                     "their elastic force [N]; rerun from the scene");
  if (version == 2)
    refuse(path, "format version 2, but this grainstorm reads version " + std::to_string(kCheckpointFormatVersion) +
                     ": version 2 had one checksum over the whole file, which every rank of a restart had to read; "
                     "continue it with the grainstorm that wrote it, or rerun from the scene");
  if (version != kCheckpointFormatVersion)
    refuse(path, "format version " + std::to_string(version) + ", but this grainstorm reads version " +
                     std::to_string(kCheckpointFormatVersion));
  if (!h5::has_attribute(f, "/", "complete") || h5::read_attribute<std::int32_t>(f, "/", "complete") != 1)
    refuse(path, "incomplete: the 'complete' marker is missing, so writing it did not finish");
}

// The HDF5 types of an array element's values (a Vec3d is stored as a row of
// three doubles, a quaternion as four floats).
template <class T>
struct Stored {
  static hid_t memory() { return h5::TypeOf<T>::memory(); }
  static hid_t file() { return h5::TypeOf<T>::file(); }
};
template <>
struct Stored<Vec3d> : Stored<double> {};
template <>
struct Stored<Quaternion> : Stored<float> {};
template <>
struct Stored<ImageCount> : Stored<std::int32_t> {};

constexpr hsize_t kBlockRows = hsize_t(1) << 20;

// Calls use(first index, positions) for blocks of the stored positions of
// particles [first, last).
void for_each_position_block_of(const h5::File& f, hsize_t n, hsize_t first, hsize_t last,
                                const std::function<void(std::size_t, const std::vector<Vec3d>&)>& use) {
  std::vector<Vec3d> x;
  for (hsize_t a = first; a < last; a += kBlockRows) {
    const hsize_t b = std::min(last, a + kBlockRows);
    x.resize(std::size_t(b - a));
    h5::read_rows_raw(f, "particles/position", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, x.data(), {n, 3}, a, b - a);
    use(std::size_t(a), x);
  }
}


// Reads the checkpoint's arrays a block of particles at a time (the blocks
// the file checksums), verifying each block it reads against its stored
// checksum, and keeps the entries of the particles in `rows` (ascending
// indices; all of them when `all`). A block that holds none of them is not
// read: each rank verifies what it reads. Host memory is one block and what
// is kept.
class ArrayStream {
 public:
  ArrayStream(const h5::File& f, hsize_t n, hsize_t block_rows, const std::vector<std::uint64_t>& sums)
      : f_(f), n_(n), block_rows_(block_rows), blocks_((n + block_rows - 1) / block_rows), sums_(sums) {}

  void keep(const std::vector<std::size_t>* rows) { rows_ = rows; }

  // Dataset `path` of shape `dims` into `out`, `per` elements per particle (1
  // for particle fields, the slots for history); dims[0] / n rows per particle
  // (the partners are stored (n, slots), the other history fields (n slots)).
  template <class T>
  void read(const std::string& path, const std::vector<hsize_t>& dims, hsize_t per, std::vector<T>& out) {
    out.clear();
    if (dims[0] == 0 || per == 0) return h5::require_shape(f_, path, dims);
    if (!rows_) out.reserve(std::size_t(n_ * per));
    std::size_t next = 0;  // the next kept row
    for_each_block<T>(path, array_++, dims, per, [&](hsize_t, hsize_t b) {
      return !rows_ || (next < rows_->size() && (*rows_)[next] < b);
    }, [&](hsize_t a, hsize_t b, const std::vector<T>& block) {
      if (!rows_) return out.insert(out.end(), block.begin(), block.end()), void();
      for (; next < rows_->size() && (*rows_)[next] < b; ++next) {
        const auto from = block.begin() + std::ptrdiff_t(((*rows_)[next] - a) * per);
        out.insert(out.end(), from, from + std::ptrdiff_t(per));
      }
    });
  }

  // Calls use(first, last, block) for the verified blocks [first, last) of
  // the array `path`, the `array`th with checksums, that `wanted(first,
  // last)` asks for.
  template <class T, class Wanted, class Use>
  void for_each_block(const std::string& path, std::size_t array, const std::vector<hsize_t>& dims, hsize_t per,
                      Wanted&& wanted, Use&& use) {
    const hsize_t along = dims[0] / n_;
    const std::size_t first_sum = array * std::size_t(blocks_);
    std::vector<T> block;
    for (hsize_t a = 0, k = 0; a < n_; a += block_rows_, ++k) {
      const hsize_t b = std::min(n_, a + block_rows_);
      if (!wanted(a, b)) continue;
      block.resize(std::size_t((b - a) * per));
      h5::read_rows_raw(f_, path, Stored<T>::memory(), Stored<T>::file(), block.data(), dims, a * along,
                        (b - a) * along);
      Fnv1a64 sum;
      sum.add_array(block);
      const std::size_t at = first_sum + std::size_t(k);
      if (at >= sums_.size())
        refuse(f_.path(), "checksums/blocks has " + std::to_string(sums_.size()) + " entries, too few for " + path);
      if (sum.value() != sums_[at])
        refuse(f_.path(), "checksum mismatch in " + path + ", particles " + std::to_string(a) + " to " +
                              std::to_string(b - 1) + ": stored " + hex64(sums_[at]) + ", data gives " +
                              hex64(sum.value()) + " (the file was damaged after it was written)");
      use(a, b, block);
    }
  }

  // Arrays read so far (each non-empty one has a checksum per block).
  std::size_t arrays() const { return array_; }
  hsize_t blocks() const { return blocks_; }

 private:
  const h5::File& f_;
  hsize_t n_, block_rows_, blocks_;
  const std::vector<std::uint64_t>& sums_;
  const std::vector<std::size_t>* rows_ = nullptr;  // null: every row
  std::size_t array_ = 0;
};

template <class T>
std::vector<hsize_t> shape_of(hsize_t entries) {
  if constexpr (std::is_same_v<T, Vec3d> || std::is_same_v<T, ImageCount>) return {entries, 3};
  else if constexpr (std::is_same_v<T, Quaternion>) return {entries, 4};
  else return {entries};
}

// Entries history field `path` holds: n * slots when the run kept it, else 0
// (a vector field is then stored as (0, 3), a scalar one not at all).
template <class T>
hsize_t history_entries(const h5::File& f, const std::string& path, hsize_t full) {
  if constexpr (std::is_same_v<T, Vec3d>) {
    const std::vector<hsize_t> dims = h5::dims_of(f, path);
    return dims.size() == 2 && dims[0] == 0 ? 0 : full;
  } else {
    return h5::exists(f, path) ? full : 0;
  }
}

// The indices of the particles whose stored position `keep` accepts, from
// the verified blocks of particles/position (array `position` of the stream).
std::vector<std::size_t> kept_rows(ArrayStream& stream, std::size_t position_array, hsize_t n,
                                   const std::function<bool(const Vec3d&)>& keep) {
  std::vector<std::size_t> rows;
  stream.for_each_block<Vec3d>("particles/position", position_array, {n, 3}, 1, [](hsize_t, hsize_t) { return true; },
                               [&](hsize_t a, hsize_t, const std::vector<Vec3d>& x) {
                                 for (std::size_t i = 0; i < x.size(); ++i)
                                   if (keep(x[i])) rows.push_back(std::size_t(a) + i);
                               });
  return rows;
}

// The header values, walls, cuts and insertion state, and the table of block
// checksums, verified against the file's checksum: every rank checks these.
Checkpoint read_header(const h5::File& f, std::vector<std::uint64_t>& block_sums) {
  Checkpoint c;
  c.step = h5::read_attribute<std::int64_t>(f, "/", "step");
  c.time = h5::read_attribute<double>(f, "/", "time");
  c.scene_hash = h5::read_attribute<std::uint64_t>(f, "/", "scene_hash");
  c.random_state = h5::read_attribute<std::uint64_t>(f, "/", "random_state");
  const hsize_t n = hsize_t(h5::read_row_count(f, "/", "particle_count", "particles/id"));
  ParticleSnapshot& p = c.particles;
  p.time = h5::read_attribute<double>(f, "particles", "time");
  p.step = h5::read_attribute<std::int64_t>(f, "particles", "step");
  HostHistory& h = c.history;
  h.slots = h5::read_attribute<std::int32_t>(f, "history", "slots");
  if (h.slots < 0 || h.slots > kMaxContactSlots)
    refuse(f.path(), "history has " + std::to_string(h.slots) + " slots per particle");
  c.walls = read_walls(f, "walls");
  c.rank_count = h5::read_attribute<std::int32_t>(f, "decomposition", "rank_count");
  c.decomposition_axis = h5::read_attribute<std::int32_t>(f, "decomposition", "axis");
  const std::vector<hsize_t> cuts = h5::dims_of(f, "decomposition/cuts");
  if (cuts.size() != 1) refuse(f.path(), "decomposition/cuts is not one-dimensional");
  c.decomposition_cuts = h5::read_array<double>(f, "decomposition/cuts", cuts);
  c.insertion = read_insertion(f);
  if (h5::exists(f, "scene_text")) {
    const std::vector<hsize_t> dims = h5::dims_of(f, "scene_text");
    if (dims.size() != 1) refuse(f.path(), "scene_text is not one-dimensional");
    const std::vector<std::uint8_t> bytes = h5::read_array<std::uint8_t>(f, "scene_text", dims);
    c.scene_text.assign(bytes.begin(), bytes.end());
  }
  const std::int64_t block_rows = h5::read_attribute<std::int64_t>(f, "checksums", "block_rows");
  if (block_rows < 1) refuse(f.path(), "checksums/block_rows is " + std::to_string(block_rows));
  c.checksum_block_rows = std::size_t(block_rows);
  const std::vector<hsize_t> table = h5::dims_of(f, "checksums/blocks");
  if (table.size() != 1) refuse(f.path(), "checksums/blocks is not one-dimensional");
  block_sums = h5::read_array<std::uint64_t>(f, "checksums/blocks", table);

  const hsize_t slots = hsize_t(h.slots);
  std::vector<std::uint64_t> history_rows;  // those the checksum counts
  for_each_history_field(h, [&](const char* name, unsigned bit, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    const hsize_t e = history_entries<T>(f, std::string("history/") + name, n * slots);
    if ((bit & kFormat2HistoryFields) != 0 || e > 0) history_rows.push_back(std::uint64_t(e));
  });
  Fnv1a64 sum;
  add_checksum_header(sum, c, std::uint64_t(n), history_rows);
  sum.add_value(std::uint64_t(c.checksum_block_rows));
  sum.add_array(block_sums);
  add_checksum_trailer(sum, c);
  const auto stored = h5::read_attribute<std::uint64_t>(f, "/", "checksum");
  if (stored != sum.value())
    refuse(f.path(), "checksum mismatch: stored " + hex64(stored) + ", the header, walls and block checksums give " +
                         hex64(sum.value()) + " (the file was damaged after it was written)");
  return c;
}

// The particle arrays: of each, the blocks that hold kept particles, each
// verified against its checksum.
void read_arrays(const h5::File& f, Checkpoint& c, hsize_t n, const std::vector<std::uint64_t>& block_sums,
                 const std::function<bool(const Vec3d&)>& keep) {
  ParticleSnapshot& p = c.particles;
  HostHistory& h = c.history;
  const hsize_t slots = hsize_t(h.slots);
  ArrayStream stream(f, n, hsize_t(c.checksum_block_rows), block_sums);
  // An optional field (ParticleField bit) is stored only by a run that kept it.
  auto stored = [&f](const std::string& path, unsigned bit) { return bit == kEveryRun || h5::exists(f, path); };
  std::size_t position_array = 0, arrays = 0;
  for_each_particle_field_bit(p, [&](const char* name, unsigned bit, auto&) {
    if (std::string(name) == "position") position_array = arrays;
    if (stored(std::string("particles/") + name, bit)) ++arrays;
  });
  std::vector<std::size_t> rows;
  if (keep) {
    rows = kept_rows(stream, position_array, n, keep);
    stream.keep(&rows);
  }
  for_each_particle_field_bit(p, [&](const char* name, unsigned bit, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    const std::string path = std::string("particles/") + name;
    if (stored(path, bit)) stream.read(path, shape_of<T>(n), 1, field);
    else field.clear();
  });
  stream.read("particles/force", shape_of<Vec3d>(n), 1, p.force);
  stream.read("particles/torque", shape_of<Vec3d>(n), 1, p.torque);
  stream.read("history/partner", {n, slots}, slots, h.partner);
  for_each_history_field(h, [&](const char* name, unsigned, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    const std::string path = std::string("history/") + name;
    const hsize_t e = history_entries<T>(f, path, n * slots);
    if (e > 0) return stream.read(path, shape_of<T>(e), slots, field);
    field.clear();
    if constexpr (std::is_same_v<T, Vec3d>) h5::require_shape(f, path, {0, 3});
  });
  const std::size_t expected = stream.arrays() * std::size_t(stream.blocks());
  if (block_sums.size() != expected)
    refuse(f.path(), "checksums/blocks has " + std::to_string(block_sums.size()) + " entries, the arrays have " +
                         std::to_string(expected) + " blocks");
}

}  // namespace

Checkpoint read_checkpoint(const std::string& path, const CheckpointExpectations& expect,
                           const std::function<bool(const Vec3d&)>& keep) {
  try {
    h5::File f = open_checked(path);
    check_header(f);
    std::vector<std::uint64_t> block_sums;
    Checkpoint c = read_header(f, block_sums);
    read_arrays(f, c, hsize_t(h5::read_row_count(f, "/", "particle_count", "particles/id")), block_sums, keep);
    if (expect.scene_hash && *expect.scene_hash != c.scene_hash)
      refuse(path, "it was written for scene hash " + hex64(c.scene_hash) + ", but this scene has hash " +
                       hex64(*expect.scene_hash) +
                       " (another scene file, or the scene was edited since: to continue the run with the edits, "
                       "add --edited-scene)");
    f.close();
    return c;
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::exception& e) {  // a missing dataset, a wrong shape, an HDF5 read error
    refuse(path, e.what());
  }
}

std::size_t checkpoint_particle_count(const std::string& path) {
  try {
    h5::File f = open_checked(path);
    check_header(f);
    return std::size_t(h5::read_row_count(f, "/", "particle_count", "particles/id"));
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::exception& e) {
    refuse(path, e.what());
  }
}

void for_each_checkpoint_position_block(const std::string& path, std::size_t first, std::size_t last,
                                        const std::function<void(std::size_t, const std::vector<Vec3d>&)>& use) {
  try {
    h5::File f = open_checked(path);
    check_header(f);
    const hsize_t n = hsize_t(h5::read_row_count(f, "/", "particle_count", "particles/id"));
    for_each_position_block_of(f, n, std::min<hsize_t>(first, n), std::min<hsize_t>(last, n), use);
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::exception& e) {
    refuse(path, e.what());
  }
}

}  // namespace gs
