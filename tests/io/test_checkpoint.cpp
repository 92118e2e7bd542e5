#include <gtest/gtest.h>

#include <array>

#include <algorithm>
#include <functional>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/checkpoint.hpp"
#include "io/fnv1a.hpp"
#include "io/h5_describe.hpp"
#include "io/h5_walls.hpp"
#include "io_test_helpers.hpp"

namespace gs {
namespace {

using test::ScratchDir;

constexpr std::uint64_t kSceneHash = 0x0123456789abcdefull;

Checkpoint sample_checkpoint(std::size_t n = 6, int slots = 4) {
  Checkpoint c;
  c.step = 123456;
  c.time = 0.1234567890123;
  c.particles = test::sample_particles(n, c.time, c.step);
  if (n > 0) {  // values a decimal round trip would lose or change
    c.particles.position[0] = {-0.0, std::numeric_limits<double>::denorm_min(), 1.0 / 3.0};
    c.particles.velocity[0] = {std::numeric_limits<double>::max(), std::nextafter(1.0, 2.0), -1e-300};
    c.particles.radius[0] = std::nextafter(0.001f, 1.0f);
  }
  c.history.slots = slots;
  for (std::size_t i = 0; i < n * std::size_t(slots); ++i) {
    c.history.partner.push_back(i % 3 == 0 ? kNoPartner : i % 3 == 1 ? ParticleId(i) : kWallPartnerBase + 1);
    c.history.tangential.push_back({1e-9 * double(i), -1.0 / double(i + 7), 0.0});
  }
  c.walls = test::sample_walls();
  c.scene_hash = kSceneHash;
  c.rank_count = 3;
  c.decomposition_axis = 2;
  c.decomposition_cuts = {0.0, 0.0333, 0.0711, 0.1};
  c.random_state = 0xfedcba9876543210ull;
  return c;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

bool same_walls(const std::vector<Wall>& a, const std::vector<Wall>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(wall_state(a[i]).data(), wall_state(b[i]).data(), sizeof(double) * kWallStateSize) != 0)
      return false;
  return true;
}

void expect_bitwise_equal(const Checkpoint& a, const Checkpoint& b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(std::memcmp(&a.time, &b.time, sizeof(double)), 0);
  EXPECT_EQ(a.particles.step, b.particles.step);
  EXPECT_EQ(std::memcmp(&a.particles.time, &b.particles.time, sizeof(double)), 0);
  const ParticleSnapshot &p = a.particles, &q = b.particles;
  EXPECT_TRUE(same_bytes(p.id, q.id));
  EXPECT_TRUE(same_bytes(p.material, q.material));
  EXPECT_TRUE(same_bytes(p.marker, q.marker));
  EXPECT_TRUE(same_bytes(p.radius, q.radius));
  EXPECT_TRUE(same_bytes(p.mass, q.mass));
  EXPECT_TRUE(same_bytes(p.inertia, q.inertia));
  EXPECT_TRUE(same_bytes(p.position, q.position));
  EXPECT_TRUE(same_bytes(p.velocity, q.velocity));
  EXPECT_TRUE(same_bytes(p.angular_velocity, q.angular_velocity));
  EXPECT_TRUE(same_bytes(p.orientation, q.orientation));
  EXPECT_TRUE(same_bytes(p.image, q.image));  // empty unless the run is periodic
  EXPECT_TRUE(same_bytes(p.force, q.force));
  EXPECT_TRUE(same_bytes(p.torque, q.torque));
  EXPECT_EQ(a.history.slots, b.history.slots);
  EXPECT_TRUE(same_bytes(a.history.partner, b.history.partner));
  for_each_history_field(a.history, b.history, [](const char* name, unsigned, const auto& x, const auto& y) {
    EXPECT_TRUE(same_bytes(x, y)) << name;
  });
  EXPECT_TRUE(same_walls(a.walls, b.walls));
  EXPECT_EQ(a.scene_hash, b.scene_hash);
  EXPECT_EQ(a.rank_count, b.rank_count);
  EXPECT_EQ(a.decomposition_axis, b.decomposition_axis);
  EXPECT_TRUE(same_bytes(a.decomposition_cuts, b.decomposition_cuts));
  EXPECT_EQ(a.random_state, b.random_state);
}

// The CheckpointError message of reading `path`, or "" when it reads.
std::string refusal(const std::string& path, const CheckpointExpectations& expect = {}) {
  try {
    read_checkpoint(path, expect);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

void copy_file(const std::string& from, const std::string& to) {
  std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing);
}

// Edits a written checkpoint in place through the C API, as damage would.
template <class Edit>
void edit_h5(const std::string& path, Edit edit) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  edit(f);
  ASSERT_GE(H5Fclose(f), 0);
}

TEST(Checkpoint, RoundTripIsBitwise) {
  ScratchDir dir;
  const Checkpoint c = sample_checkpoint();
  const std::string path = dir.file(checkpoint_h5_name(c.step));
  write_checkpoint(path, c);
  const Checkpoint back = read_checkpoint(path, {kSceneHash});
  expect_bitwise_equal(c, back);
  EXPECT_TRUE(back.history.rolling.empty());
  EXPECT_EQ(checkpoint_checksum(back), checkpoint_checksum(c));
  EXPECT_EQ(test::read_h5_attribute<std::uint64_t>(path, "/", "checksum", H5T_NATIVE_UINT64), checkpoint_checksum(c));
}

// The block checksums are summed on several threads: each must still be the
// FNV-1a (by its definition, byte by byte) of its own block, in the table's
// order (each array's blocks in row order, the arrays as docs/OUTPUT.md lists
// them), whatever thread summed it. Blocks of 7 rows: 143 per array.
std::uint64_t fnv_by_definition(const void* data, std::size_t bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t k = 0; k < bytes; ++k) h = (h ^ static_cast<const unsigned char*>(data)[k]) * 1099511628211ull;
  return h;
}

TEST(Checkpoint, BlockChecksumsAreEachBlocksFnvInTableOrder) {
  Checkpoint c = sample_checkpoint(1000, 3);
  c.checksum_block_rows = 7;
  std::vector<std::uint64_t> expected;
  auto blocks_of = [&](const auto& v, std::size_t per) {
    const std::size_t row = per * sizeof(v[0]);
    for (std::size_t a = 0; a < 1000; a += 7)
      expected.push_back(fnv_by_definition(reinterpret_cast<const char*>(v.data()) + a * row,
                                           std::min<std::size_t>(7, 1000 - a) * row));
  };
  const ParticleSnapshot& p = c.particles;
  ASSERT_TRUE(p.image.empty() && p.frozen.empty());  // optional fields not kept: no blocks
  blocks_of(p.id, 1);
  blocks_of(p.material, 1);
  blocks_of(p.marker, 1);
  blocks_of(p.radius, 1);
  blocks_of(p.mass, 1);
  blocks_of(p.inertia, 1);
  blocks_of(p.position, 1);
  blocks_of(p.velocity, 1);
  blocks_of(p.angular_velocity, 1);
  blocks_of(p.orientation, 1);
  blocks_of(p.force, 1);
  blocks_of(p.torque, 1);
  blocks_of(c.history.partner, 3);
  blocks_of(c.history.tangential, 3);
  EXPECT_EQ(checkpoint_block_checksums(c), expected);
}

// The hysteretic model's peak overlaps: written and read back bit for bit;
// a run that does not keep them writes no dataset, so its file (and its
// checksum) is what format 2 was before the field existed.
TEST(Checkpoint, PeakOverlapsRoundTripAndAreAbsentWhenNotKept) {
  ScratchDir dir;
  Checkpoint c = sample_checkpoint();
  for (std::size_t e = 0; e < c.history.partner.size(); ++e) c.history.peak_overlap.push_back(1e-7 * double(e) / 3);
  const std::string with = dir.file("with.h5"), without = dir.file("without.h5");
  write_checkpoint(with, c);
  const Checkpoint back = read_checkpoint(with);
  expect_bitwise_equal(c, back);
  EXPECT_EQ(back.history.peak_overlap.size(), c.history.partner.size());
  write_checkpoint(without, sample_checkpoint());
  EXPECT_TRUE(read_checkpoint(without).history.peak_overlap.empty());
  const hid_t f = H5Fopen(without.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(H5Lexists(f, "history/peak_overlap", H5P_DEFAULT), 0);
  ASSERT_GE(H5Fclose(f), 0);
}

TEST(Checkpoint, RoundTripWithoutParticlesOrHistory) {
  ScratchDir dir;
  const Checkpoint c = sample_checkpoint(0, 0);
  write_checkpoint(dir.file("empty.h5"), c);
  expect_bitwise_equal(c, read_checkpoint(dir.file("empty.h5")));
}

TEST(Checkpoint, AtomicWriteLeavesNoTemporaryFile) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  Checkpoint later = sample_checkpoint();
  later.step += 1000;
  write_checkpoint(path, later);  // replaces the previous one
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"checkpoint.h5"});
  EXPECT_EQ(read_checkpoint(path).step, later.step);

  // A write that fails half way removes its temporary file and keeps the old checkpoint.
  EXPECT_THROW(write_atomically(path,
                                [](const std::string& temporary) {
                                  std::ofstream(temporary) << "half a checkpoint";
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"checkpoint.h5"});
  EXPECT_EQ(read_checkpoint(path).step, later.step);
}

TEST(Checkpoint, InconsistentArraysAreRefusedBeforeWriting) {
  ScratchDir dir;
  Checkpoint c = sample_checkpoint();
  c.particles.torque.pop_back();
  EXPECT_THROW(write_checkpoint(dir.file("c.h5"), c), std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Checkpoint, TruncatedFileIsRefusedAndThePreviousOneStillReads) {
  ScratchDir dir;
  const std::string good = dir.file("checkpoint_0000001000.h5"), cut = dir.file("checkpoint_0000002000.h5");
  write_checkpoint(good, sample_checkpoint());
  copy_file(good, cut);
  std::filesystem::resize_file(cut, std::filesystem::file_size(cut) / 2);
  const std::string why = refusal(cut);
  EXPECT_NE(why.find(cut), std::string::npos) << why;
  EXPECT_NE(why.find("truncated"), std::string::npos) << why;
  EXPECT_EQ(refusal(good), "");

  std::filesystem::resize_file(cut, 5);  // not even the HDF5 signature is left
  EXPECT_NE(refusal(cut).find("not an HDF5 file"), std::string::npos) << refusal(cut);
}

TEST(Checkpoint, FileThatIsNotHdf5IsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  { std::ofstream(path) << "step: 12\n"; }
  EXPECT_NE(refusal(path).find("not an HDF5 file"), std::string::npos) << refusal(path);
  EXPECT_NE(refusal(dir.file("absent.h5")).find("no such file"), std::string::npos);
  std::filesystem::create_directory(dir.file("run"));
  EXPECT_NE(refusal(dir.file("run")).find("a directory, not a checkpoint file"), std::string::npos)
      << refusal(dir.file("run"));
}

TEST(Checkpoint, FlippedByteIsCaughtByTheChecksum) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  haddr_t offset = HADDR_UNDEF;
  edit_h5(path, [&](hid_t f) {
    const hid_t d = H5Dopen2(f, "particles/position", H5P_DEFAULT);
    offset = H5Dget_offset(d);
    H5Dclose(d);
  });
  ASSERT_NE(offset, HADDR_UNDEF);
  {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekg(std::streamoff(offset + 29));
    const char byte = char(file.get() ^ 0x10);
    file.seekp(std::streamoff(offset + 29));
    file.put(byte);
  }
  const std::string why = refusal(path);
  EXPECT_NE(why.find("checksum mismatch"), std::string::npos) << why;
  EXPECT_NE(why.find(path), std::string::npos) << why;
}

// A rank of a restart reads only the particles it keeps, with their history
// rows, from a file read in blocks (more particles than one block holds), and
// they are bitwise those of the whole read.
TEST(Checkpoint, PartReadHoldsTheKeptParticlesWithTheirHistory) {
  ScratchDir dir;
  const std::size_t n = (std::size_t(1) << 20) + 4099;
  Checkpoint c = sample_checkpoint(n, 2);
  for (std::size_t e = 0; e < c.history.partner.size(); ++e) c.history.peak_overlap.push_back(1e-9 * double(e));
  // Image counts, as a periodic run keeps them: streamed like the other fields.
  for (std::size_t i = 0; i < n; ++i)
    c.particles.image.push_back({std::int32_t(i % 7) - 3, -std::int32_t(i % 5), std::int32_t(i >> 18)});
  const std::string path = dir.file("big.h5");
  write_checkpoint(path, c);
  // x = 0.1 + i / 3: whole runs of ids on either side of block boundaries.
  auto keep = [](const Vec3d& x) { return std::fmod(x.x, 1000.0) < 300.0 || (x.x > 349500 && x.x < 349600); };
  const Checkpoint part = read_checkpoint(path, {kSceneHash}, keep);
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < n; ++i)
    if (keep(c.particles.position[i])) rows.push_back(i);
  ASSERT_GT(rows.size(), n / 4);
  ASSERT_LT(rows.size(), n / 2);
  Checkpoint expected = c;
  auto pick = [&rows](auto& v, std::size_t per) {
    std::decay_t<decltype(v)> out;
    for (std::size_t r : rows) out.insert(out.end(), v.begin() + std::ptrdiff_t(r * per),
                                          v.begin() + std::ptrdiff_t((r + 1) * per));
    v = out;
  };
  // An optional field the run does not keep (image) is empty.
  for_each_particle_field(expected.particles, [&](const char*, auto& field) {
    if (!field.empty()) pick(field, 1);
  });
  pick(expected.particles.force, 1);
  pick(expected.particles.torque, 1);
  pick(expected.history.partner, 2);
  for_each_history_field(expected.history, [&](const char*, unsigned, auto& field) {
    if (!field.empty()) pick(field, 2);
  });
  expect_bitwise_equal(expected, part);
}

// Each block of each array has its own checksum, verified by the reader that
// reads that block: a rank of a restart reads (and verifies) the blocks that
// hold its particles, all of particles/position, and the header.
Checkpoint blocked_checkpoint() {
  Checkpoint c = sample_checkpoint(100, 2);
  c.checksum_block_rows = 10;
  return c;
}

// Particles [first, last) by their stored positions.
std::function<bool(const Vec3d&)> rows_of(const Checkpoint& c, std::size_t first, std::size_t last) {
  std::vector<Vec3d> x(c.particles.position.begin() + std::ptrdiff_t(first),
                       c.particles.position.begin() + std::ptrdiff_t(last));
  return [x](const Vec3d& p) {
    return std::any_of(x.begin(), x.end(), [&p](const Vec3d& q) { return std::memcmp(&p, &q, sizeof(Vec3d)) == 0; });
  };
}

void damage_row(const std::string& path, const char* dataset, std::size_t row) {
  edit_h5(path, [&](hid_t f) {
    const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
    std::vector<double> v(300);
    ASSERT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    v[3 * row + 1] += 1;
    ASSERT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    H5Dclose(d);
  });
}

std::string refusal_keeping(const std::string& path, const std::function<bool(const Vec3d&)>& keep) {
  try {
    read_checkpoint(path, {}, keep);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

TEST(Checkpoint, DamageIsCaughtByTheRankThatReadsIt) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  const Checkpoint c = blocked_checkpoint();
  write_checkpoint(path, c);
  ASSERT_EQ(refusal_keeping(path, rows_of(c, 0, 100)), "");
  damage_row(path, "particles/velocity", 95);
  // A rank whose particles lie in blocks 0-4 reads none of the damage.
  EXPECT_EQ(refusal_keeping(path, rows_of(c, 0, 50)), "");
  const Checkpoint part = read_checkpoint(path, {}, rows_of(c, 0, 50));
  ASSERT_EQ(part.particles.size(), 50u);
  EXPECT_EQ(std::memcmp(part.particles.velocity.data(), c.particles.velocity.data(), 50 * sizeof(Vec3d)), 0);
  // The rank that holds particle 92 reads block 9 and refuses it, naming the array and the block.
  const std::string why = refusal_keeping(path, rows_of(c, 92, 93));
  EXPECT_NE(why.find("checksum mismatch in particles/velocity, particles 90 to 99"), std::string::npos) << why;
  EXPECT_NE(why.find(path), std::string::npos) << why;
  EXPECT_NE(refusal(path).find("checksum mismatch in particles/velocity"), std::string::npos) << refusal(path);
}

TEST(Checkpoint, DamageToPositionsOrHeaderIsCaughtByEveryRank) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  const Checkpoint c = blocked_checkpoint();
  write_checkpoint(path, c);
  damage_row(path, "particles/position", 95);  // every rank reads the positions to find its own
  const auto none = [](const Vec3d&) { return false; };
  EXPECT_NE(refusal_keeping(path, none).find("checksum mismatch in particles/position"), std::string::npos);
  write_checkpoint(path, c);
  edit_h5(path, [](hid_t f) {
    const hid_t a = H5Aopen(f, "time", H5P_DEFAULT);
    const double t = 0.5;
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_DOUBLE, &t), 0);
    H5Aclose(a);
  });
  EXPECT_NE(refusal_keeping(path, none).find("checksum mismatch: stored"), std::string::npos) << refusal_keeping(path, none);
}

// Version 2 had one checksum over the whole file: refused, naming the version.
TEST(Checkpoint, VersionTwoIsRefusedWithTheReason) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) {
    const hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
    const std::int32_t version = 2;
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT32, &version), 0);
    H5Aclose(a);
  });
  const std::string why = refusal(path);
  EXPECT_NE(why.find("format version 2, but this grainstorm reads version 3"), std::string::npos) << why;
}

TEST(Checkpoint, WrongSceneIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  const std::string why = refusal(path, {scene_hash("another scene")});
  EXPECT_NE(why.find("scene hash 0x0123456789abcdef"), std::string::npos) << why;
  EXPECT_EQ(refusal(path, {kSceneHash}), "");
  EXPECT_EQ(refusal(path, {}), "") << "no expectation, no check";
}

// The scene file's text travels in the checkpoint (for a restart with an
// edited scene to list the edits), under the checksum; a checkpoint without
// it (written before it was stored) still reads, with the text empty.
TEST(Checkpoint, TheSceneTextRoundTripsUnderTheChecksum) {
  ScratchDir dir;
  Checkpoint c = sample_checkpoint();
  c.scene_text = "domain: {min: [0, 0, 0], max: [1, 1, 1]}\n# a comment with a byte \xff\n";
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, c);
  EXPECT_EQ(read_checkpoint(path).scene_text, c.scene_text);

  const std::string edited = dir.file("edited.h5");
  copy_file(path, edited);
  edit_h5(edited, [](hid_t f) {
    const hid_t d = H5Dopen2(f, "scene_text", H5P_DEFAULT);
    ASSERT_GE(d, 0);
    std::vector<std::uint8_t> bytes(8);
    const hid_t memory = H5Screate_simple(1, std::array<hsize_t, 1>{8}.data(), nullptr);
    const hid_t file = H5Dget_space(d);
    const hsize_t start = 0, count = 8;
    H5Sselect_hyperslab(file, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
    ASSERT_GE(H5Dread(d, H5T_NATIVE_UINT8, memory, file, H5P_DEFAULT, bytes.data()), 0);
    bytes[2] ^= 0x01;
    ASSERT_GE(H5Dwrite(d, H5T_NATIVE_UINT8, memory, file, H5P_DEFAULT, bytes.data()), 0);
    H5Sclose(file);
    H5Sclose(memory);
    H5Dclose(d);
  });
  const std::string why = refusal(edited);
  EXPECT_NE(why.find("checksum mismatch"), std::string::npos) << why;

  Checkpoint without = sample_checkpoint();
  const std::string older = dir.file("older.h5");
  write_checkpoint(older, without);
  EXPECT_EQ(refusal(older), "");
  EXPECT_TRUE(read_checkpoint(older).scene_text.empty());
  edit_h5(older, [](hid_t f) { EXPECT_EQ(H5Lexists(f, "scene_text", H5P_DEFAULT), 0); });
}

TEST(Checkpoint, MissingDatasetIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) { ASSERT_GE(H5Ldelete(f, "particles/torque", H5P_DEFAULT), 0); });
  const std::string why = refusal(path);
  EXPECT_NE(why.find("missing dataset"), std::string::npos) << why;
  EXPECT_NE(why.find("/particles/torque"), std::string::npos) << why;
}

TEST(Checkpoint, OtherFormatVersionIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) {
    const hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
    const std::int32_t version = 99;
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT32, &version), 0);
    H5Aclose(a);
  });
  EXPECT_NE(refusal(path).find("format version 99"), std::string::npos) << refusal(path);
}

// Version 1 stored the tangential springs as displacements; the incremental
// friction law carries forces, so such a file cannot be continued.
TEST(Checkpoint, VersionOneIsRefusedWithTheReason) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) {
    const hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
    const std::int32_t version = 1;
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT32, &version), 0);
    H5Aclose(a);
  });
  const std::string why = refusal(path);
  EXPECT_NE(why.find("format version 1, but this grainstorm reads version " + std::to_string(kCheckpointFormatVersion)),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("tangential springs as displacements"), std::string::npos) << why;
}

TEST(Checkpoint, UnfinishedFileIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) { ASSERT_GE(H5Adelete(f, "complete"), 0); });
  EXPECT_NE(refusal(path).find("'complete' marker is missing"), std::string::npos) << refusal(path);
}

// particle_count = 2^33 with datasets of 6 rows: refused, naming the
// attribute, the dataset and both sizes, before anything is allocated for it
// (std::bad_alloc before).
TEST(Checkpoint, ParticleCountThatDisagreesWithTheDatasetsIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) {
    const hid_t a = H5Aopen(f, "particle_count", H5P_DEFAULT);
    const std::int64_t count = std::int64_t(1) << 33;
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT64, &count), 0);
    H5Aclose(a);
  });
  const std::string why = refusal(path);
  for (const char* expected : {"particle_count", "8589934592", "/particles/id", "shape (6)", path.c_str()})
    EXPECT_NE(why.find(expected), std::string::npos) << "missing '" << expected << "' in: " << why;
  EXPECT_EQ(why.find("bad_alloc"), std::string::npos) << why;
  // info still reads the header, then reports the file as damaged.
  EXPECT_THROW(describe_h5(path), h5::FormatError);
}

// A dataset whose rows disagree with the others is refused by its shape.
TEST(Checkpoint, DatasetOfTheWrongShapeIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) {
    ASSERT_GE(H5Ldelete(f, "particles/velocity", H5P_DEFAULT), 0);
    const hsize_t dims[2] = {5, 3};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t d = H5Dcreate2(f, "particles/velocity", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(d, 0);
    H5Dclose(d);
    H5Sclose(space);
  });
  const std::string why = refusal(path);
  EXPECT_NE(why.find("/particles/velocity has shape (5, 3), expected (6, 3)"), std::string::npos) << why;
}

TEST(Checkpoint, DescribeReportsIntegrity) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  const H5Description d = describe_h5(path);
  EXPECT_FALSE(d.damaged);
  const std::string& text = d.text;
  for (const char* expected : {"kind:          checkpoint", "step 123456", "particles:     6",
                               "history:       4 slots per particle, tangential springs yes, rolling springs no",
                               "decomposition: 3 rank(s), slab axis z", "scene hash:    0x0123456789abcdef",
                               "scene text:    not stored", "integrity:     complete, checksum matches"})
    EXPECT_NE(text.find(expected), std::string::npos) << "missing '" << expected << "' in\n" << text;
  Checkpoint with_text = sample_checkpoint();
  with_text.scene_text = "gravity: [0, 0, -9.81]\n";
  write_checkpoint(path, with_text);
  const std::string described = describe_h5(path).text;
  EXPECT_NE(described.find("scene text:    23 bytes (dataset scene_text)"), std::string::npos) << described;
}

TEST(Checkpoint, DescribeFlagsADamagedCheckpoint) {
  ScratchDir dir;
  const std::string path = dir.file("checkpoint.h5");
  write_checkpoint(path, sample_checkpoint());
  edit_h5(path, [](hid_t f) { ASSERT_GE(H5Adelete(f, "complete"), 0); });
  const H5Description d = describe_h5(path);
  EXPECT_TRUE(d.damaged);
  EXPECT_NE(d.text.find("integrity:     DAMAGED: "), std::string::npos) << d.text;
}

}  // namespace
}  // namespace gs
