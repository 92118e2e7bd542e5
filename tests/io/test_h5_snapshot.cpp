#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "io/fnv1a.hpp"
#include "io/h5_check.hpp"
#include "io/h5_describe.hpp"
#include "io/h5_io.hpp"
#include "io/h5_snapshot.hpp"
#include "io_test_helpers.hpp"

namespace gs {
namespace {

using test::read_h5;
using test::ScratchDir;

SnapshotMetadata sample_metadata(std::size_t n) {
  SnapshotMetadata m;
  m.scene_hash = scene_hash("domain: {min: [0, 0, 0], max: [1, 1, 1]}\n");
  m.scene_path = "cases/demo/settle.yaml";
  m.wall_names = {"floor", "drum"};
  for (std::size_t i = 0; i < n; ++i) m.contact_count.push_back(std::uint16_t(i % 5));
  return m;
}

TEST(SnapshotFields, ParsesNamesAndAlwaysKeepsPosition) {
  const SnapshotFields f = parse_snapshot_fields({"id", "velocity", "contact_count", "velocity"});
  EXPECT_EQ(f.names(), (std::vector<std::string>{"id", "position", "velocity", "contact_count"}));
  EXPECT_EQ(parse_snapshot_fields({}).names(), std::vector<std::string>{"position"});
}

TEST(SnapshotFields, UnknownNameIsRefusedByName) {
  try {
    parse_snapshot_fields({"id", "veloctiy"});
    FAIL() << "an unknown field was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown snapshot field 'veloctiy'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("angular_velocity"), std::string::npos) << "lists the known fields";
  }
}

TEST(Snapshot, RoundTripThroughTheCApi) {
  ScratchDir dir;
  const ParticleSnapshot s = test::sample_particles(5);
  const SnapshotMetadata m = sample_metadata(s.size());
  const SnapshotFields fields =
      parse_snapshot_fields({"id", "material", "marker", "radius", "velocity", "orientation", "force", "contact_count"});
  const std::string path = dir.file(snapshot_h5_name(s.step));
  write_snapshot(path, s, fields, test::sample_walls(), m);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"particles_0000000250.h5"}) << "no temporary file left";

  EXPECT_EQ(test::read_h5_attribute<double>(path, "/", "time", H5T_NATIVE_DOUBLE), s.time);
  EXPECT_EQ(test::read_h5_attribute<std::int64_t>(path, "/", "step", H5T_NATIVE_INT64), s.step);
  EXPECT_EQ(test::read_h5_attribute<std::uint64_t>(path, "/", "scene_hash", H5T_NATIVE_UINT64), m.scene_hash);
  EXPECT_EQ(test::read_h5_string(path, "/", "grainstorm_version"), GS_VERSION);
  EXPECT_EQ(test::read_h5_string(path, "/", "units"), "SI: m, kg, s, N, rad");
  EXPECT_EQ(test::read_h5_string(path, "particles/velocity", "units"), "m/s");

  for (const std::string& name : fields.names()) EXPECT_TRUE(test::h5_link_exists(path, "particles/" + name)) << name;
  for (const char* absent : {"mass", "inertia", "angular_velocity", "torque"})
    EXPECT_FALSE(test::h5_link_exists(path, std::string("particles/") + absent)) << absent;

  std::vector<hsize_t> dims;
  EXPECT_EQ(read_h5<std::uint32_t>(path, "particles/id", H5T_NATIVE_UINT32, &dims), s.id);
  EXPECT_EQ(dims, (std::vector<hsize_t>{5}));
  EXPECT_EQ(read_h5<std::uint8_t>(path, "particles/material", H5T_NATIVE_UINT8), s.material);
  EXPECT_EQ(read_h5<std::uint8_t>(path, "particles/marker", H5T_NATIVE_UINT8), s.marker);
  EXPECT_EQ(read_h5<float>(path, "particles/radius", H5T_NATIVE_FLOAT), s.radius);
  EXPECT_EQ(read_h5<std::uint16_t>(path, "particles/contact_count", H5T_NATIVE_UINT16), m.contact_count);
  const auto x = read_h5<double>(path, "particles/position", H5T_NATIVE_DOUBLE, &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{5, 3}));
  const auto v = read_h5<double>(path, "particles/velocity", H5T_NATIVE_DOUBLE);
  const auto q = read_h5<float>(path, "particles/orientation", H5T_NATIVE_FLOAT, &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{5, 4}));
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(x[3 * i + 0], s.position[i].x);
    EXPECT_EQ(x[3 * i + 2], s.position[i].z);
    EXPECT_EQ(v[3 * i + 1], s.velocity[i].y);
    EXPECT_EQ(q[4 * i + 0], s.orientation[i].w);
    EXPECT_EQ(q[4 * i + 3], s.orientation[i].z);
  }
}

TEST(Snapshot, WallsAreDescribedForDrawing) {
  ScratchDir dir;
  const std::string path = dir.file("walls.h5");
  const std::vector<Wall> walls = test::sample_walls();
  write_snapshot(path, test::sample_particles(2), SnapshotFields(), walls, sample_metadata(2));
  EXPECT_EQ(read_h5<std::int32_t>(path, "walls/kind", H5T_NATIVE_INT32), (std::vector<std::int32_t>{0, 2}));
  EXPECT_EQ(read_h5<double>(path, "walls/radius", H5T_NATIVE_DOUBLE), (std::vector<double>{0, 0.1}));
  std::vector<hsize_t> dims;
  const auto rotation = read_h5<double>(path, "walls/rotation", H5T_NATIVE_DOUBLE, &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 3, 3}));
  EXPECT_EQ(rotation[9 + 2], 0.6);
  // Current pose of the drum's base centre: R (p - axis_point) + axis_point + shift.
  const auto now = read_h5<double>(path, "walls/current_point", H5T_NATIVE_DOUBLE);
  EXPECT_DOUBLE_EQ(now[3 + 0], 0.01);
  EXPECT_DOUBLE_EQ(now[3 + 1], -0.05);
  EXPECT_DOUBLE_EQ(now[3 + 2], 0.1);
  EXPECT_EQ(test::read_h5_string(path, "walls", "names"), "floor\ndrum");
}

TEST(Snapshot, EmptySnapshotIsValid) {
  ScratchDir dir;
  const std::string path = dir.file("empty.h5");
  write_snapshot(path, test::sample_particles(0), default_snapshot_fields(), {}, SnapshotMetadata());
  std::vector<hsize_t> dims;
  EXPECT_TRUE(read_h5<double>(path, "particles/position", H5T_NATIVE_DOUBLE, &dims).empty());
  EXPECT_EQ(dims, (std::vector<hsize_t>{0, 3}));
}

TEST(Snapshot, SelectedFieldWithoutDataIsRefused) {
  ScratchDir dir;
  const SnapshotFields fields = parse_snapshot_fields({"contact_count"});
  EXPECT_THROW(write_snapshot(dir.file("a.h5"), test::sample_particles(3), fields, {}, SnapshotMetadata()),
               std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Snapshot, DescribeSummarisesIt) {
  ScratchDir dir;
  const std::string path = dir.file("s.h5");
  const ParticleSnapshot s = test::sample_particles(4);
  write_snapshot(path, s, default_snapshot_fields(), test::sample_walls(), sample_metadata(4));
  const std::string text = describe_h5(path).text;
  for (const char* expected : {"kind:          snapshot", "time:          0.125 s, step 250",
                               "particles:     4", "bounding box:  [0.1, -0.628571, 0.111111] to [1.1, -0.2, 0.114111]",
                               "walls:         2 (1 plane, 0 disk, 1 cylinder)", "scene hash:    0x", GS_VERSION,
                               "fields:        angular_velocity id marker material position radius velocity"})
    EXPECT_NE(text.find(expected), std::string::npos) << "missing '" << expected << "' in\n" << text;
}

// A particle_count of 2^33 over datasets of 4 rows: a FormatError naming the
// attribute, the dataset and both sizes, not std::bad_alloc.
TEST(Snapshot, ParticleCountThatDisagreesWithTheDatasetsIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("s.h5");
  write_snapshot(path, test::sample_particles(4), default_snapshot_fields(), {}, SnapshotMetadata());
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t a = H5Aopen(f, "particle_count", H5P_DEFAULT);
  const std::int64_t count = std::int64_t(1) << 33;
  ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT64, &count), 0);
  H5Aclose(a);
  H5Fclose(f);
  for (auto read : {+[](const std::string& p) { read_snapshot(p); }, +[](const std::string& p) { describe_h5(p); }}) {
    try {
      read(path);
      ADD_FAILURE() << "read a snapshot whose particle_count disagrees with its datasets";
    } catch (const h5::FormatError& e) {
      const std::string why = e.what();
      for (const char* expected : {"particle_count", "8589934592", "/particles/position", "shape (4, 3)", "s.h5"})
        EXPECT_NE(why.find(expected), std::string::npos) << "missing '" << expected << "' in: " << why;
    }
  }
}

TEST(Snapshot, DescribeRefusesOtherFiles) {
  ScratchDir dir;
  const std::string path = dir.file("notes.h5");
  { std::ofstream(path) << "not hdf5\n"; }
  EXPECT_THROW(describe_h5(path), std::runtime_error);
  EXPECT_THROW(describe_h5(dir.file("missing.h5")), std::runtime_error);
}

TEST(H5Check, FailedCallNamesTheCallAndTheFile) {
  try {
    h5::File::open_read_only("/nonexistent-dir/x.h5");
    FAIL() << "opened a missing file";
  } catch (const h5::H5Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("H5Fopen"), std::string::npos) << what;
    EXPECT_NE(what.find("/nonexistent-dir/x.h5"), std::string::npos) << what;
  }
}

TEST(SceneHash, IsFnv1a64) {
  EXPECT_EQ(scene_hash(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(scene_hash("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(scene_hash("foobar"), 0x85944171f73967e8ull);
}

}  // namespace
}  // namespace gs
