// The `grainstorm` command as a user meets it: bad scenes and options are
// refused before anything is written, with the offending key on stderr; the
// informational commands succeed.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "backend/cpu/cpu_arch.hpp"

namespace gs::test {
namespace {

namespace fs = std::filesystem;

// A valid scene (one sphere above a floor), small enough to run in an instant.
const std::string kGoodScene = R"(domain: {min: [0, 0, -0.005], max: [0.01, 0.01, 0.01]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
walls:
  - plane: {point: [0, 0, 0], normal: [0, 0, 1]}
    material: glass
    name: floor
particles:
  - list:
      - {position: [0.005, 0.005, 0.002], radius: 0.001, material: glass}
time_step: {fraction_of_contact_time: 0.1}
duration: 0.001
output: {directory: scene_out}
)";

struct CliResult {
  int exit_code;
  std::string out, err;
};

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Each test gets a fresh directory: `work` (the command's working directory,
// holding scene.yaml) and, beside it, the captured stdout and stderr.
class CliTest : public testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "gs_cli_XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    root_ = pattern;
    work_ = root_ / "work";
    fs::create_directory(work_);
  }
  void TearDown() override { fs::remove_all(root_); }

  CliResult run_cli(const std::string& args) const {
    const std::string command = "cd '" + work_.string() + "' && '" GS_CLI_PATH "' " + args + " > '" +
                                (root_ / "stdout").string() + "' 2> '" + (root_ / "stderr").string() + "'";
    const int status = std::system(command.c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return {code, read_file(root_ / "stdout"), read_file(root_ / "stderr")};
  }

  void write_scene(const std::string& text) const { std::ofstream(work_ / "scene.yaml") << text; }

  std::vector<std::string> work_entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(work_)) names.push_back(e.path().filename().string());
    return names;
  }

  // `run` on `scene` fails, names `key` on stderr and writes nothing: neither
  // the --out directory nor the scene's own output directory appears.
  void expect_refused(const std::string& scene, const std::string& key, const std::string& extra_args = "") const {
    write_scene(scene);
    const CliResult r = run_cli("run scene.yaml --backend cpu --out out_dir " + extra_args);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find(key), std::string::npos) << "stderr does not name '" << key << "':\n" << r.err;
    EXPECT_EQ(work_entries(), std::vector<std::string>{"scene.yaml"}) << "something was written";
    if (!extra_args.empty()) return;  // the scene itself is fine
    const CliResult c = run_cli("check scene.yaml");
    EXPECT_NE(c.exit_code, 0);
    EXPECT_NE(c.err.find(key), std::string::npos) << "check: stderr does not name '" << key << "':\n" << c.err;
  }

  fs::path root_, work_;
};

// kGoodScene with `from` replaced by `to`.
std::string edit(const std::string& from, const std::string& to) {
  std::string text = kGoodScene;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' is not in the scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The reference for the failures below: the unedited scene checks, runs and
// writes its output.
TEST_F(CliTest, GoodSceneRunsAndWrites) {
  write_scene(kGoodScene);
  EXPECT_EQ(run_cli("check scene.yaml").exit_code, 0);
  const CliResult r = run_cli("run scene.yaml --backend cpu --steps 3 --out out_dir");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_directory(work_ / "out_dir"));
  EXPECT_FALSE(fs::is_empty(work_ / "out_dir"));
}

TEST_F(CliTest, UnknownKey) { expect_refused(edit("gravity:", "gravty:"), "gravty"); }

TEST_F(CliTest, MissingKey) { expect_refused(edit("duration: 0.001\n", ""), "duration"); }

TEST_F(CliTest, NegativeRadius) {
  expect_refused(edit("radius: 0.001", "radius: -0.001"), "particles[0].list[0].radius");
}

TEST_F(CliTest, RestitutionAboveOne) {
  expect_refused(edit("restitution: 0.5", "restitution: 1.5"), "pairs[0].restitution");
}

TEST_F(CliTest, ParticleOutsideDomain) {
  expect_refused(edit("[0.005, 0.005, 0.002]", "[0.005, 0.005, 0.0095]"), "particles[0].list[0]");
}

TEST_F(CliTest, ParticleCutsWall) {
  expect_refused(edit("[0.005, 0.005, 0.002]", "[0.005, 0.005, 0.0005]"), "wall 'floor'");
}

TEST_F(CliTest, TimeStepAboveStabilityLimit) {
  expect_refused(edit("fraction_of_contact_time: 0.1", "fraction_of_contact_time: 0.5"), "time_step");
}

// Issue 18: what `run` refused (or ran badly) `check` refuses too, before
// anything is written.
TEST_F(CliTest, HugeDomain) {
  expect_refused(edit("max: [0.01, 0.01, 0.01]", "max: [1e7, 1e7, 1e7]"), "scene.yaml:1: domain");
  expect_refused(edit("max: [0.01, 0.01, 0.01]", "max: [1e30, 1e30, 1e30]"), "scene.yaml:1: domain");
}

TEST_F(CliTest, ContactCountWithoutFriction) {
  expect_refused(edit("output: {directory: scene_out}",
                      "output: {directory: scene_out, fields: [id, position, contact_count]}"),
                 "scene.yaml:16: output.fields: contact_count needs a contact history");
}

TEST_F(CliTest, MeshInMillimetres) {
  // A 300 mm plate read as 300 m under a 1.5 cm domain.
  const std::string stl = (root_ / "plate_mm.stl").string();
  std::ofstream(stl) << "solid plate\nfacet normal 0 0 1\nouter loop\nvertex -100 -100 -1\nvertex 200 -100 -1\n"
                        "vertex 200 200 -1\nendloop\nendfacet\nendsolid plate\n";
  expect_refused(edit("particles:", "  - mesh: {stl: " + stl + "}\n    material: glass\nparticles:"),
                 "scene.yaml:11: walls[1].mesh: mesh 'mesh' spans [300, 300, 0] m");
}

TEST_F(CliTest, WarnsOfIgnoredFriction) {
  write_scene(edit("restitution: 0.5}", "restitution: 0.5, friction: 0.5}"));
  const std::string warning = "warning: scene.yaml:6: pairs[0].friction: ignored: the effect friction is off";
  const CliResult c = run_cli("check scene.yaml");
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.err.find(warning), std::string::npos) << c.err;
  const CliResult r = run_cli("run scene.yaml --backend cpu --steps 3 --out out_dir");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(warning), std::string::npos) << r.err;
  write_scene(kGoodScene);
  EXPECT_EQ(run_cli("check scene.yaml").err, "");
}

TEST_F(CliTest, UnknownOption) { expect_refused(kGoodScene, "--bogus", "--bogus"); }

// --steps is a whole number >= 0, all of its text; an option given twice or
// without a value is refused (one value would be dropped without a word).
TEST_F(CliTest, BadStepsAndRepeatedOptions) {
  for (const char* steps : {"abc", "10x", "1e3", "-1", "-5", "99999999999999999999"})
    expect_refused(kGoodScene,
                   std::string("--steps must be a whole number >= 0 (the step to end at), got '") + steps + "'",
                   std::string("--steps ") + steps);
  expect_refused(kGoodScene, "option --steps given twice", "--steps 5 --steps 10");
  expect_refused(kGoodScene, "option --out given twice", "--out other");
  expect_refused(kGoodScene, "option --steps needs a value", "--steps ''");
}

// A directory given as the scene is named as such (it used to read as an
// empty scene: "expected a map").
TEST_F(CliTest, DirectoryForAScene) {
  fs::create_directory(work_ / "scenes");
  for (const char* command : {"check scenes", "run scenes --backend cpu"}) {
    const CliResult r = run_cli(command);
    EXPECT_NE(r.exit_code, 0) << command;
    EXPECT_NE(r.err.find("scenes:1: scene: a directory, not a scene file"), std::string::npos) << r.err;
  }
}

// An output directory that cannot be made is named as such.
TEST_F(CliTest, OutputDirectoryThatCannotBeMade) {
  write_scene(kGoodScene);
  const CliResult r = run_cli("run scene.yaml --backend cpu --steps 3 --out scene.yaml/sub");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("cannot create the output directory scene.yaml/sub"), std::string::npos) << r.err;
  EXPECT_EQ(work_entries(), std::vector<std::string>{"scene.yaml"});
}

TEST_F(CliTest, BadExchangeOption) {
  expect_refused(kGoodScene, "--exchange", "--exchange nccl2");
  expect_refused(kGoodScene, "--exchange device needs --backend cuda", "--exchange device");
}

TEST_F(CliTest, VersionAndHelp) {
  const CliResult v = run_cli("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.out, std::string("grainstorm " GS_VERSION " (host code for ") + gs::host_code_arch() + ")\n");
  const CliResult h = run_cli("--help");
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("usage:"), std::string::npos);
  for (const char* option : {"--overwrite", "--restart", "--out", "--steps"})
    EXPECT_NE(h.out.find(option), std::string::npos) << option;
  // A command's --help is the usage too, not a scene file called --help.
  for (const char* args : {"-h", "help", "run --help", "run scene.yaml --steps 3 --help", "check -h", "info --help",
                           "mixing --help"}) {
    const CliResult c = run_cli(args);
    EXPECT_EQ(c.exit_code, 0) << args << ": " << c.err;
    EXPECT_EQ(c.out, h.out) << args;
  }
  EXPECT_TRUE(work_entries().empty());
}

TEST_F(CliTest, CheckDemoScene) {
  const CliResult r = run_cli("check '" GS_SOURCE_DIR "/cases/demo/settle.yaml'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("is valid"), std::string::npos);
  EXPECT_NE(r.out.find("verlet skin:    0.1 largest diameters"), std::string::npos) << r.out;
  EXPECT_TRUE(work_entries().empty());  // check writes nothing
}

// 300 spheres falling in a box, marked at the start by x, analysed every
// 100 steps in the run and snapshotted at the same steps.
const std::string kMixingScene = R"(domain: {min: [0, 0, 0], max: [0.03, 0.03, 0.03]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5}
walls:
  - box: {min: [0, 0, 0], max: [0.03, 0.03, 0.03]}
    material: glass
particles:
  - random_fill:
      {material: glass, region: {box: {min: [0.001, 0.001, 0.001], max: [0.029, 0.029, 0.029]}}, count: 300,
       radius: 0.001, seed: 3}
marking: {time: 0, plane: {point: [0.015, 0, 0], normal: [1, 0, 0]}, front: 1, back: 0}
time_step: {absolute: 0.00004}
duration: 0.012
output: {interval: 0.004, directory: res, fields: [id, material, marker, radius, position]}
analysis:
  mixing:
    center: [0.015, 0.015]
    bottom: 0.001
    height: 0.02
    rings: {inner_radius: 0.002, outer_radius: 0.012, count: 2}
    sample_radius: 0.002
    every: 0.004
    min_particles: 1
    min_fill: 0
)";

// A mixing log in a directory that does not exist: `run` used to create the
// output directory, run.log and timeseries.csv before failing.
TEST_F(CliTest, MixingLogInMissingDirectory) {
  std::string scene = kMixingScene;
  scene.replace(scene.find("    min_fill: 0\n"), 16, "    min_fill: 0\n    output: " +
                (root_ / "missing" / "mix.csv").string() + "\n");
  expect_refused(scene, "analysis.mixing.output: the directory");
  scene = kMixingScene;
  scene.replace(scene.find("    min_fill: 0\n"), 16, "    min_fill: 0\n    output: sub/mix.csv\n");
  expect_refused(scene, "analysis.mixing.output: a relative path");
}

// `grainstorm mixing` over the run's snapshots reproduces the run's own
// analysis row for row (the masses are recomputed from radius and density,
// as the run computed them); with --layers it samples more, smaller cells;
// bad input is refused and leaves no log.
TEST_F(CliTest, MixingOverSnapshotsEqualsTheRunsAnalysis) {
  write_scene(kMixingScene);
  const CliResult r = run_cli("run scene.yaml --backend cpu");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string snaps = "res/particles_0000000000.h5 res/particles_0000000100.h5 res/particles_0000000200.h5 "
                            "res/particles_0000000300.h5";
  const CliResult m = run_cli("mixing scene.yaml " + snaps + " --out again.csv");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const std::string run_log = read_file(work_ / "res" / "mixing.csv"), again = read_file(work_ / "again.csv");
  EXPECT_EQ(std::count(run_log.begin(), run_log.end(), '\n'), 5) << run_log;
  EXPECT_EQ(again, run_log);
  const CliResult l = run_cli("mixing scene.yaml " + snaps + " --out layered.csv --layers 2");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_NE(l.out.find("of 2 layers"), std::string::npos) << l.out;
  EXPECT_NE(read_file(work_ / "layered.csv"), run_log);
  const std::string bad_runs[] = {"mixing scene.yaml res/run.log --out bad.csv", "mixing scene.yaml " + snaps,
                                  "mixing scene.yaml " + snaps + " --out bad.csv --layers 0"};
  for (const std::string& bad : bad_runs) {
    const CliResult b = run_cli(bad);
    EXPECT_NE(b.exit_code, 0) << bad;
    EXPECT_FALSE(b.err.empty()) << bad;
    EXPECT_FALSE(fs::exists(work_ / "bad.csv")) << bad;
  }
}

}  // namespace
}  // namespace gs::test
