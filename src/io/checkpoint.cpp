#include "io/checkpoint.hpp"

#include <algorithm>
#include <cstdio>
#include <future>

#include "io/atomic_file.hpp"
#include "io/checkpoint_insertion.hpp"
#include "io/fnv1a.hpp"
#include "io/h5_io.hpp"
#include "io/h5_walls.hpp"

namespace gs {
namespace {

void require_length(std::size_t actual, std::size_t expected, const char* field, const std::string& path) {
  if (actual != expected)
    throw std::invalid_argument("write_checkpoint " + path + ": " + field + " has " + std::to_string(actual) +
                                " values, expected " + std::to_string(expected));
}

void validate(const Checkpoint& c, const std::string& path) {
  const ParticleSnapshot& p = c.particles;
  const std::size_t n = p.size();
  // An optional field (ParticleField bit) is empty when the run does not keep it.
  for_each_particle_field_bit(p, [&](const char* name, unsigned bit, const auto& field) {
    if (bit == kEveryRun || !field.empty()) require_length(field.size(), n, name, path);
  });
  require_length(p.force.size(), n, "force", path);
  require_length(p.torque.size(), n, "torque", path);
  const HostHistory& h = c.history;
  if (h.slots < 0 || h.slots > kMaxContactSlots)
    throw std::invalid_argument("write_checkpoint " + path + ": history has " + std::to_string(h.slots) + " slots");
  const std::size_t entries = n * std::size_t(h.slots);
  require_length(h.partner.size(), entries, "history partner", path);
  for_each_history_field(h, [&](const char* name, unsigned, const auto& field) {
    if (!field.empty()) require_length(field.size(), entries, ("history " + std::string(name)).c_str(), path);
  });
}

void write_particles(const h5::File& f, const ParticleSnapshot& p) {
  h5::create_group(f, "particles");
  h5::write_attribute(f, "particles", "time", p.time);
  h5::write_attribute(f, "particles", "step", std::int64_t(p.step));
  for_each_particle_field_bit(p, [&](const char* name, unsigned bit, const auto& field) {
    if (bit == kEveryRun || !field.empty()) h5::write_field(f, std::string("particles/") + name, field);
  });
  h5::write_vec3(f, "particles/force", p.force);
  h5::write_vec3(f, "particles/torque", p.torque);
}

// A history field of n * slots entries: (entries, 3) for vectors, (entries) for scalars.
void write_history_field(const h5::File& f, const std::string& path, const std::vector<Vec3d>& v) {
  h5::write_vec3(f, path, v);
}
void write_history_field(const h5::File& f, const std::string& path, const std::vector<double>& v) {
  h5::write_vector(f, path, v);
}

void write_history(const h5::File& f, const HostHistory& h, std::size_t n) {
  h5::create_group(f, "history");
  h5::write_attribute(f, "history", "slots", std::int32_t(h.slots));
  h5::write_array(f, "history/partner", h.partner.data(), {hsize_t(n), hsize_t(h.slots)});
  // Format 2's fields always, empty when not kept; later fields only when kept.
  for_each_history_field(h, [&](const char* name, unsigned bit, const auto& field) {
    if ((bit & kFormat2HistoryFields) != 0 || !field.empty()) write_history_field(f, std::string("history/") + name, field);
  });
}

void write_decomposition(const h5::File& f, const Checkpoint& c) {
  h5::create_group(f, "decomposition");
  h5::write_attribute(f, "decomposition", "rank_count", std::int32_t(c.rank_count));
  h5::write_attribute(f, "decomposition", "axis", std::int32_t(c.decomposition_axis));
  h5::write_vector(f, "decomposition/cuts", c.decomposition_cuts);
}

}  // namespace

std::string checkpoint_h5_name(long long step) {
  char name[64];
  std::snprintf(name, sizeof(name), "checkpoint_%010lld.h5", step);
  return name;
}

void add_checksum_header(Fnv1a64& sum, const Checkpoint& c, std::uint64_t particles,
                         const std::vector<std::uint64_t>& history_rows) {
  sum.add_value(std::int32_t(kCheckpointFormatVersion));
  sum.add_value(std::int64_t(c.step));
  sum.add_value(c.time);
  sum.add_value(std::int64_t(c.particles.step));
  sum.add_value(c.particles.time);
  sum.add_value(c.scene_hash);
  sum.add_value(std::int32_t(c.rank_count));
  sum.add_value(std::int32_t(c.decomposition_axis));
  sum.add_value(c.random_state);
  sum.add_value(particles);
  sum.add_value(std::int32_t(c.history.slots));
  for (std::uint64_t rows : history_rows) sum.add_value(rows);
  sum.add_value(std::uint64_t(c.walls.size()));
  sum.add_value(std::uint64_t(c.decomposition_cuts.size()));
}

std::vector<std::uint64_t> checkpoint_block_checksums(const Checkpoint& c) {
  const ParticleSnapshot& p = c.particles;
  const HostHistory& h = c.history;
  const std::size_t n = p.size(), rows = c.checksum_block_rows, slots = std::size_t(std::max(0, h.slots));
  struct Block {
    const unsigned char* bytes;
    std::size_t count;
  };
  std::vector<Block> blocks;  // in the table's order
  auto add = [&](const auto& field, std::size_t per) {
    if (field.empty()) return;  // an array the run does not keep
    const auto* bytes = reinterpret_cast<const unsigned char*>(field.data());
    const std::size_t row_bytes = per * sizeof(field[0]);
    for (std::size_t a = 0; a < n; a += rows)
      blocks.push_back({bytes + a * row_bytes, (std::min(n, a + rows) - a) * row_bytes});
  };
  for_each_particle_field(p, [&](const char*, const auto& field) { add(field, 1); });
  add(p.force, 1);
  add(p.torque, 1);
  add(h.partner, slots);
  for_each_history_field(h, [&](const char*, unsigned, const auto& field) { add(field, slots); });
  // FNV-1a is one serial multiply per byte, but the blocks are independent:
  // summed on every host thread (a checkpoint of 24e6 frictional spheres
  // holds about 200 blocks of 1e6 rows).
  std::vector<std::uint64_t> sums(blocks.size());
  const auto count = static_cast<std::ptrdiff_t>(blocks.size());
#pragma omp parallel for schedule(dynamic, 1) if (count > 1)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    Fnv1a64 sum;
    sum.add(blocks[std::size_t(k)].bytes, blocks[std::size_t(k)].count);
    sums[std::size_t(k)] = sum.value();
  }
  return sums;
}

std::uint64_t checkpoint_checksum(const Checkpoint& c) { return checkpoint_checksum(c, checkpoint_block_checksums(c)); }

std::uint64_t checkpoint_checksum(const Checkpoint& c, const std::vector<std::uint64_t>& block_checksums) {
  const HostHistory& h = c.history;
  std::vector<std::uint64_t> history_rows;
  for_each_history_field(h, [&](const char*, unsigned bit, const auto& field) {
    if ((bit & kFormat2HistoryFields) != 0 || !field.empty()) history_rows.push_back(field.size());
  });
  Fnv1a64 sum;
  add_checksum_header(sum, c, c.particles.size(), history_rows);
  sum.add_value(std::uint64_t(c.checksum_block_rows));
  sum.add_array(block_checksums);
  add_checksum_trailer(sum, c);
  return sum.value();
}

void add_checksum_trailer(Fnv1a64& sum, const Checkpoint& c) {
  for (const Wall& w : c.walls) {
    const auto state = wall_state(w);
    sum.add(state.data(), sizeof(state));
  }
  sum.add_array(c.decomposition_cuts);
  if (c.insertion) add_insertion(sum, *c.insertion);
  // Only when stored, so that the checksums of older files stay valid.
  if (!c.scene_text.empty()) {
    sum.add_value(std::uint64_t(c.scene_text.size()));
    sum.add(c.scene_text.data(), c.scene_text.size());
  }
}

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  validate(c, path);
  // The checksum (one serial pass over every byte) is summed on a thread of
  // its own while the datasets are written; it is needed only at the end.
  if (c.checksum_block_rows == 0) throw std::invalid_argument("write_checkpoint " + path + ": checksum blocks of 0 rows");
  std::vector<std::uint64_t> blocks;
  std::future<std::uint64_t> checksum = std::async(std::launch::async, [&c, &blocks] {
    blocks = checkpoint_block_checksums(c);
    return checkpoint_checksum(c, blocks);
  });
  write_atomically(path, [&](const std::string& temporary) {
    h5::File f = h5::File::create(temporary);
    h5::write_string_attribute(f, "/", "kind", "grainstorm checkpoint");
    h5::write_attribute(f, "/", "format_version", std::int32_t(kCheckpointFormatVersion));
    h5::write_string_attribute(f, "/", "grainstorm_version", GS_VERSION);
    h5::write_attribute(f, "/", "step", std::int64_t(c.step));
    h5::write_attribute(f, "/", "time", c.time);
    h5::write_attribute(f, "/", "scene_hash", c.scene_hash);
    h5::write_attribute(f, "/", "random_state", c.random_state);
    h5::write_attribute(f, "/", "particle_count", std::int64_t(c.particles.size()));
    h5::write_string_attribute(f, "/", "units", "SI: m, kg, s, N, rad");
    write_particles(f, c.particles);
    write_history(f, c.history, c.particles.size());
    write_walls(f, "walls", c.walls, {});
    write_decomposition(f, c);
    if (c.insertion) write_insertion(f, *c.insertion);
    if (!c.scene_text.empty())
      h5::write_vector(f, "scene_text", std::vector<std::uint8_t>(c.scene_text.begin(), c.scene_text.end()));
    const std::uint64_t whole = checksum.get();
    h5::create_group(f, "checksums");
    h5::write_attribute(f, "checksums", "block_rows", std::int64_t(c.checksum_block_rows));
    h5::write_vector(f, "checksums/blocks", blocks);
    h5::write_attribute(f, "/", "checksum", whole);
    // Last: a file without the marker was not finished.
    h5::write_attribute(f, "/", "complete", std::int32_t(1));
    f.close();
  });
}

}  // namespace gs
