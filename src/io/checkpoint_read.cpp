// read_checkpoint: every way a checkpoint can be unusable ends in a
// CheckpointError that names the file and the cause.
#include <cinttypes>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <functional>
#include <type_traits>

#include "io/checkpoint.hpp"
#include "io/checkpoint_insertion.hpp"
#include "io/h5_io.hpp"
#include "io/h5_walls.hpp"

namespace gs {
namespace {

std::string hex(std::uint64_t x) {
  char s[24];
  std::snprintf(s, sizeof(s), "0x%016" PRIx64, x);
  return s;
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw CheckpointError("checkpoint " + path + " refused: " + why);
}

h5::File open_checked(const std::string& path) {
  std::error_code ec;
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


// Reads the checkpoint's arrays a block of particles at a time, adding each
// block to the checksum in the order checkpoint_checksum gives (so the file is
// verified whole), and keeps the entries of the particles in `rows` (ascending
// indices; all of them when `all`). Host memory is one block and what is kept.
class ArrayStream {
 public:
  ArrayStream(const h5::File& f, hsize_t n, const std::vector<std::size_t>& rows, bool all, Fnv1a64& sum)
      : f_(f), n_(n), rows_(rows), all_(all), sum_(sum) {}

  // Dataset `path` of shape `dims` into `out`, `per` elements per particle (1
  // for particle fields, the slots for history); dims[0] / n rows per particle
  // (the partners are stored (n, slots), the other history fields (n slots)).
  template <class T>
  void read(const std::string& path, const std::vector<hsize_t>& dims, hsize_t per, std::vector<T>& out) {
    out.clear();
    if (dims[0] == 0) return h5::require_shape(f_, path, dims);
    const hsize_t along = dims[0] / n_;
    if (all_) out.reserve(std::size_t(n_ * per));
    std::vector<T> block;
    std::size_t next = 0;  // the next kept row
    for (hsize_t a = 0; a < n_; a += kBlockRows) {
      const hsize_t b = std::min(n_, a + kBlockRows);
      block.resize(std::size_t((b - a) * per));
      h5::read_rows_raw(f_, path, Stored<T>::memory(), Stored<T>::file(), block.data(), dims, a * along,
                         (b - a) * along);
      sum_.add_array(block);
      if (all_) {
        out.insert(out.end(), block.begin(), block.end());
        continue;
      }
      for (; next < rows_.size() && rows_[next] < b; ++next) {
        const auto from = block.begin() + std::ptrdiff_t((rows_[next] - a) * per);
        out.insert(out.end(), from, from + std::ptrdiff_t(per));
      }
    }
  }

 private:
  const h5::File& f_;
  hsize_t n_;
  const std::vector<std::size_t>& rows_;
  bool all_;
  Fnv1a64& sum_;
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

// The indices of the particles whose stored position `keep` accepts.
std::vector<std::size_t> kept_rows(const h5::File& f, hsize_t n, const std::function<bool(const Vec3d&)>& keep) {
  std::vector<std::size_t> rows;
  for_each_position_block_of(f, n, 0, n, [&](std::size_t first, const std::vector<Vec3d>& x) {
    for (std::size_t i = 0; i < x.size(); ++i)
      if (keep(x[i])) rows.push_back(first + i);
  });
  return rows;
}

Checkpoint read_contents(const h5::File& f, const std::function<bool(const Vec3d&)>& keep, std::uint64_t& checksum) {
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
  const hsize_t slots = hsize_t(h.slots);
  c.walls = read_walls(f, "walls");
  c.rank_count = h5::read_attribute<std::int32_t>(f, "decomposition", "rank_count");
  c.decomposition_axis = h5::read_attribute<std::int32_t>(f, "decomposition", "axis");
  const std::vector<hsize_t> cuts = h5::dims_of(f, "decomposition/cuts");
  if (cuts.size() != 1) refuse(f.path(), "decomposition/cuts is not one-dimensional");
  c.decomposition_cuts = h5::read_array<double>(f, "decomposition/cuts", cuts);
  c.insertion = read_insertion(f);

  std::vector<hsize_t> entries;  // per history field
  for_each_history_field(h, [&](const char* name, unsigned, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    entries.push_back(history_entries<T>(f, std::string("history/") + name, n * slots));
  });

  std::vector<std::uint64_t> history_rows;  // those the checksum counts
  {
    std::size_t k = 0;
    for_each_history_field(h, [&](const char*, unsigned bit, auto&) {
      const hsize_t e = entries[k++];
      if ((bit & kFormat2HistoryFields) != 0 || e > 0) history_rows.push_back(std::uint64_t(e));
    });
  }
  Fnv1a64 sum;
  add_checksum_header(sum, c, std::uint64_t(n), history_rows);

  const bool all = !keep;
  const std::vector<std::size_t> rows = all ? std::vector<std::size_t>() : kept_rows(f, n, keep);
  ArrayStream stream(f, n, rows, all, sum);
  // An optional field (ParticleField bit) is stored only by a run that kept
  // it, and counts in the checksum only then (checkpoint_checksum).
  for_each_particle_field_bit(p, [&](const char* name, unsigned bit, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    const std::string path = std::string("particles/") + name;
    if (bit == kEveryRun || h5::exists(f, path)) stream.read(path, shape_of<T>(n), 1, field);
    else field.clear();
  });
  stream.read("particles/force", shape_of<Vec3d>(n), 1, p.force);
  stream.read("particles/torque", shape_of<Vec3d>(n), 1, p.torque);
  stream.read("history/partner", {n, slots}, slots, h.partner);
  std::size_t k = 0;
  for_each_history_field(h, [&](const char* name, unsigned, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    const hsize_t e = entries[k++];
    const std::string path = std::string("history/") + name;
    if (e > 0) return stream.read(path, shape_of<T>(e), slots, field);
    field.clear();
    if constexpr (std::is_same_v<T, Vec3d>) h5::require_shape(f, path, {0, 3});
  });
  for (const Wall& w : c.walls) {
    const auto state = wall_state(w);
    sum.add(state.data(), sizeof(state));
  }
  sum.add_array(c.decomposition_cuts);
  if (c.insertion) add_insertion(sum, *c.insertion);
  checksum = sum.value();
  return c;
}

}  // namespace

Checkpoint read_checkpoint(const std::string& path, const CheckpointExpectations& expect,
                           const std::function<bool(const Vec3d&)>& keep) {
  try {
    h5::File f = open_checked(path);
    check_header(f);
    std::uint64_t computed = 0;
    Checkpoint c = read_contents(f, keep, computed);
    const auto stored = h5::read_attribute<std::uint64_t>(f, "/", "checksum");
    if (stored != computed)
      refuse(path, "checksum mismatch: stored " + hex(stored) + ", data gives " + hex(computed) +
                       " (the file was damaged after it was written)");
    if (expect.scene_hash && *expect.scene_hash != c.scene_hash)
      refuse(path, "it was written for scene hash " + hex(c.scene_hash) + ", but this scene has hash " +
                       hex(*expect.scene_hash) + " (another scene file, or the scene was edited since)");
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
