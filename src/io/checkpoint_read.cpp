// read_checkpoint: every way a checkpoint can be unusable ends in a
// CheckpointError that names the file and the cause.
#include <cinttypes>
#include <cstdio>
#include <filesystem>

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

ParticleSnapshot read_particles(const h5::File& f, hsize_t n) {
  ParticleSnapshot p;
  p.time = h5::read_attribute<double>(f, "particles", "time");
  p.step = h5::read_attribute<std::int64_t>(f, "particles", "step");
  for_each_particle_field(p, [&](const char* name, auto& field) {
    h5::read_field(f, std::string("particles/") + name, n, field);
  });
  p.force = h5::read_vec3(f, "particles/force", n);
  p.torque = h5::read_vec3(f, "particles/torque", n);
  return p;
}

// A history field is kept only when the run's model and effects use it:
// (0, 3) or (n * slots, 3) for vectors, absent or (n * slots) for scalars
// (kFormat2HistoryFields are always present).
void read_history_field(const h5::File& f, const std::string& path, hsize_t entries, std::vector<Vec3d>& out) {
  const std::vector<hsize_t> dims = h5::dims_of(f, path);
  const hsize_t rows = dims.size() == 2 && dims[0] == 0 ? 0 : entries;
  out = h5::read_vec3(f, path, rows);
}
void read_history_field(const h5::File& f, const std::string& path, hsize_t entries, std::vector<double>& out) {
  if (!h5::exists(f, path)) return out.clear();
  out = h5::read_array<double>(f, path, {entries});
}

HostHistory read_history(const h5::File& f, hsize_t n) {
  HostHistory h;
  h.slots = h5::read_attribute<std::int32_t>(f, "history", "slots");
  if (h.slots < 0 || h.slots > kMaxContactSlots)
    refuse(f.path(), "history has " + std::to_string(h.slots) + " slots per particle");
  const hsize_t slots = hsize_t(h.slots);
  h.partner = h5::read_array<ParticleId>(f, "history/partner", {n, slots});
  for_each_history_field(h, [&](const char* name, unsigned, auto& field) {
    read_history_field(f, std::string("history/") + name, n * slots, field);
  });
  return h;
}

Checkpoint read_contents(const h5::File& f) {
  Checkpoint c;
  c.step = h5::read_attribute<std::int64_t>(f, "/", "step");
  c.time = h5::read_attribute<double>(f, "/", "time");
  c.scene_hash = h5::read_attribute<std::uint64_t>(f, "/", "scene_hash");
  c.random_state = h5::read_attribute<std::uint64_t>(f, "/", "random_state");
  const auto n = h5::read_row_count(f, "/", "particle_count", "particles/id");
  c.particles = read_particles(f, hsize_t(n));
  c.history = read_history(f, hsize_t(n));
  c.walls = read_walls(f, "walls");
  c.rank_count = h5::read_attribute<std::int32_t>(f, "decomposition", "rank_count");
  c.decomposition_axis = h5::read_attribute<std::int32_t>(f, "decomposition", "axis");
  const std::vector<hsize_t> cuts = h5::dims_of(f, "decomposition/cuts");
  if (cuts.size() != 1) refuse(f.path(), "decomposition/cuts is not one-dimensional");
  c.decomposition_cuts = h5::read_array<double>(f, "decomposition/cuts", cuts);
  c.insertion = read_insertion(f);
  return c;
}

}  // namespace

Checkpoint read_checkpoint(const std::string& path, const CheckpointExpectations& expect) {
  try {
    h5::File f = open_checked(path);
    check_header(f);
    Checkpoint c = read_contents(f);
    const auto stored = h5::read_attribute<std::uint64_t>(f, "/", "checksum");
    const std::uint64_t computed = checkpoint_checksum(c);
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

}  // namespace gs
