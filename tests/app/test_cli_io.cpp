// The `grainstorm` command on output files: `info` exits non-zero on a
// damaged checkpoint and on a file whose counts disagree with its data, and
// --help lists every run option.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/checkpoint.hpp"
#include "io/io_test_helpers.hpp"

namespace gs::test {
namespace {

struct CliResult {
  int exit_code;
  std::string out, err;
};

std::string read_text(const std::string& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliResult run_cli(const ScratchDir& dir, const std::string& args) {
  const std::string command =
      "'" GS_CLI_PATH "' " + args + " > '" + dir.file("stdout") + "' 2> '" + dir.file("stderr") + "'";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(dir.file("stdout")), read_text(dir.file("stderr"))};
}

std::string a_checkpoint(const ScratchDir& dir) {
  Checkpoint c;
  c.step = 40;
  c.time = 0.004;
  c.particles = sample_particles(5, c.time, c.step);
  c.history.slots = 2;
  c.history.partner.assign(10, kNoPartner);
  c.history.tangential.assign(10, Vec3d());
  c.walls = sample_walls();
  const std::string path = dir.file(checkpoint_h5_name(c.step));
  write_checkpoint(path, c);
  return path;
}

// Flips one bit of the bytes of dataset `dataset` in place.
void flip_a_byte(const std::string& path, const char* dataset) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
  const haddr_t offset = H5Dget_offset(d);
  H5Dclose(d);
  H5Fclose(f);
  ASSERT_NE(offset, HADDR_UNDEF);
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(std::streamoff(offset + 3));
  const char byte = char(file.get() ^ 0x04);
  file.seekp(std::streamoff(offset + 3));
  file.put(byte);
}

TEST(CliInfo, IntactCheckpointExitsZero) {
  ScratchDir dir;
  const CliResult r = run_cli(dir, "info '" + a_checkpoint(dir) + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("integrity:     complete, checksum matches"), std::string::npos) << r.out;
}

TEST(CliInfo, DamagedCheckpointExitsNonZero) {
  ScratchDir dir;
  const std::string path = a_checkpoint(dir);
  flip_a_byte(path, "particles/velocity");
  const CliResult r = run_cli(dir, "info '" + path + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("integrity:     DAMAGED: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("checksum mismatch"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find(path + " is damaged"), std::string::npos) << r.err;
}

TEST(CliInfo, ParticleCountBeyondTheDataIsAnErrorNotBadAlloc) {
  ScratchDir dir;
  const std::string path = a_checkpoint(dir);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t a = H5Aopen(f, "particle_count", H5P_DEFAULT);
  const std::int64_t count = std::int64_t(1) << 33;
  ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT64, &count), 0);
  H5Aclose(a);
  H5Fclose(f);
  const CliResult r = run_cli(dir, "info '" + path + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("'particle_count'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("8589934592"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/particles/position has shape (5, 3)"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A run in a box of six planes, checkpointed at step 92 and restarted from it
// into the same directory: the XDMF index keeps the six wall surfaces of
// every snapshot, those written before the restart (read back from the
// files) and after.
TEST(CliRun, RestartKeepsTheWallsInTheIndex) {
  ScratchDir dir;
  std::ofstream(dir.file("box.yaml")) << R"(domain: {min: [-0.001, -0.001, -0.001], max: [0.021, 0.021, 0.041]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
walls:
  - box: {min: [0, 0, 0], max: [0.02, 0.02, 0.04]}
    material: glass
particles:
  - random_fill:
      {material: glass, region: {box: {min: [0.001, 0.001, 0.001], max: [0.019, 0.019, 0.039]}}, count: 50,
       radius: 0.0008, seed: 3}
time_step: {absolute: 0.00002}
duration: 0.004
output: {interval: 0.001, format: hdf5, checkpoint_interval: 0.002}
)";
  const std::string out = dir.file("out");
  const CliResult first = run_cli(dir, "run '" + dir.file("box.yaml") + "' --backend cpu --out '" + out + "'");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const CliResult again = run_cli(dir, "run '" + dir.file("box.yaml") + "' --backend cpu --out '" + out +
                                           "' --restart '" + out + "/checkpoint_0000000100.h5'");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const std::string xdmf = read_text(out + "/particles.xdmf");
  EXPECT_EQ(count(xdmf, "<Grid Name=\"step_"), 5u) << xdmf;
  EXPECT_EQ(count(xdmf, "<Grid Name=\"walls_"), 5u) << xdmf;
  EXPECT_EQ(count(xdmf, "<Grid Name=\"box.zmin\""), 5u) << xdmf;
  EXPECT_EQ(count(xdmf, ":/wall_surfaces/5/vertices"), 5u) << xdmf;
  EXPECT_EQ(count(xdmf, ":/wall_surfaces/6/"), 0u) << xdmf;
}

TEST(CliHelp, ListsEveryRunOption) {
  ScratchDir dir;
  const CliResult r = run_cli(dir, "--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option : {"--backend", "--steps", "--out", "--exchange", "--restart"})
    EXPECT_NE(r.out.find(option), std::string::npos) << option << " missing from --help:\n" << r.out;
}

}  // namespace
}  // namespace gs::test
