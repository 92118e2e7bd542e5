// I/O errors name the file and carry the system's reason. CI runs as root,
// where permissions do not fail, so the failures are made otherwise: a path
// under a regular file (ENOTDIR), /dev/full (ENOSPC on write), a target that
// is a directory (EISDIR on rename).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/particle_csv.hpp"
#include "io/text_file.hpp"
#include "io/xdmf_series.hpp"
#include "io_test_helpers.hpp"

namespace gs {
namespace {

using test::ScratchDir;

// The message of the std::runtime_error that f throws, or "" when none.
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

void expect_mentions(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& p : parts) EXPECT_NE(message.find(p), std::string::npos) << "'" << p << "' not in: " << message;
}

// "<dir>/plain/<name>": "plain" is a regular file, so opening fails with ENOTDIR.
std::string under_a_file(const ScratchDir& dir, const std::string& name) {
  std::ofstream(dir.file("plain")) << "a file, not a directory\n";
  return dir.file("plain") + "/" + name;
}

// The temporary file of `path` is a link to /dev/full: every write to it fails with ENOSPC.
void temporary_on_a_full_disk(const std::string& path) {
  std::filesystem::create_symlink("/dev/full", temporary_path_for(path));
}

TEST(TextFile, OpenNamesTheFileAndTheReason) {
  ScratchDir dir;
  const std::string path = under_a_file(dir, "run.log");
  expect_mentions(error_of([&] { open_for_writing(path, "a"); }), {"cannot write " + path, "Not a directory"});
}

TEST(TextFile, FullDiskIsReportedAtTheFlush) {
  std::FILE* f = open_for_writing("/dev/full", "a");
  std::fprintf(f, "step,time\n");
  expect_mentions(error_of([&] { flush_checked(f, "/dev/full"); }),
                  {"error writing /dev/full", "No space left on device"});
  std::fclose(f);
  expect_mentions(error_of([] { write_text_file("/dev/full", std::string(100000, 'x')); }),
                  {"error writing /dev/full", "No space left on device"});
}

TEST(TextFile, XdmfIndexOnAFullDisk) {
  ScratchDir dir;
  const std::string path = dir.file("particles.xdmf");
  temporary_on_a_full_disk(path);
  expect_mentions(error_of([&] { write_xdmf_series(path, {}); }),
                  {"error writing " + temporary_path_for(path), "No space left on device"});
  EXPECT_TRUE(dir.entries().empty()) << "the temporary file is removed, no index appears";
  expect_mentions(error_of([&] { write_xdmf_series(under_a_file(dir, "particles.xdmf"), {}); }),
                  {"cannot write", "Not a directory"});
}

TEST(TextFile, CsvSnapshotOnAFullDiskAndUnderAFile) {
  ScratchDir dir;
  const std::string path = dir.file(snapshot_file_name(7));
  temporary_on_a_full_disk(path);
  expect_mentions(error_of([&] { write_particles_csv(path, test::sample_particles(3)); }),
                  {"error writing " + temporary_path_for(path), "No space left on device"});
  EXPECT_TRUE(dir.entries().empty());
  expect_mentions(error_of([&] { write_particles_csv(under_a_file(dir, "p.csv"), test::sample_particles(3)); }),
                  {"cannot write", "p.csv.tmp", "Not a directory"});
  // And a good one is written under its name, with no temporary file left.
  std::filesystem::remove(dir.file("plain"));
  write_particles_csv(path, test::sample_particles(3));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{snapshot_file_name(7)});
}

TEST(TextFile, RenameOntoADirectoryGivesTheReason) {
  ScratchDir dir;
  const std::string path = dir.file("index.xdmf");
  std::filesystem::create_directories(path + "/inside");
  expect_mentions(error_of([&] { write_atomically(path, [](const std::string& t) { write_text_file(t, "x"); }); }),
                  {"cannot rename", path, "Is a directory"});
}

}  // namespace
}  // namespace gs
