#include "run/output_directory.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace gs {
namespace {

namespace fs = std::filesystem;

// Files a run writes with a step in their name; a `.tmp<pid>` suffix is a
// temporary one left by a killed run.
const std::regex kStepFile(R"((particles|meshes|checkpoint|fault)_([0-9]{10})\.(h5|csv)(\.tmp[0-9]*)?)");
// The measurements' grids (docs/MEASUREMENTS.md), average_<name>_<step>.h5,
// and their logs and indexes.
const std::regex kGridFile(R"(average_[A-Za-z0-9_-]+_([0-9]{10})\.h5(\.tmp[0-9]*)?)");
const std::regex kMeasurementFile(R"((flow|average)_[A-Za-z0-9_-]+\.(csv|xdmf)(\.tmp[0-9]*)?)");

std::string mixing_log_name(const SceneSpec& scene) {
  if (!scene.mixing) return "";
  const fs::path p(scene.mixing->output);
  return p.is_absolute() ? "" : p.lexically_normal().string();
}

bool is_run_file(const std::string& name) {
  static const std::regex fixed(R"((run\.log|timeseries\.csv|removed\.csv|inlets\.csv|particles\.xdmf|meshes\.xdmf)(\.tmp[0-9]*)?)");
  return std::regex_match(name, kStepFile) || std::regex_match(name, fixed) || std::regex_match(name, kGridFile) ||
         std::regex_match(name, kMeasurementFile);
}

void remove_file(const fs::path& p) {
  std::error_code e;
  fs::remove(p, e);
  if (e) throw std::runtime_error("cannot remove " + p.string() + ": " + e.message());
}

// Keeps the header lines (not starting with a digit) and the rows whose
// `column` (0-based) holds a step <= `step`; replaced atomically.
void keep_rows_up_to(const fs::path& csv, int column, long long step) {
  if (!fs::exists(csv)) return;
  std::ifstream in(csv);
  if (!in) throw std::runtime_error("cannot read " + csv.string());
  std::ostringstream kept;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string value;
    for (int k = 0; k <= column && std::getline(fields, value, ','); ++k) {}
    const bool row = !line.empty() && line[0] >= '0' && line[0] <= '9';
    if (!row || std::stoll(value) <= step) kept << line << '\n';
  }
  const fs::path tmp = csv.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << kept.str();
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::error_code e;
  fs::rename(tmp, csv, e);
  if (e) throw std::runtime_error("cannot replace " + csv.string() + ": " + e.message());
}

}  // namespace

void check_output_directory(const std::string& directory, OutputDirectoryUse use) {
  std::error_code e;
  if (use != OutputDirectoryUse::fresh || !fs::exists(directory, e)) return;
  if (!fs::is_directory(directory, e))
    throw std::runtime_error("the output directory " + directory + " exists and is not a directory");
  fs::directory_iterator it(directory, e);
  if (e) throw std::runtime_error("cannot read the output directory " + directory + ": " + e.message());
  if (it == fs::directory_iterator()) return;
  throw std::runtime_error("the output directory " + directory + " is not empty (it holds " +
                           it->path().filename().string() +
                           "): give --overwrite to replace an earlier run's files, --restart to continue a run in "
                           "it, or another --out");
}

void prepare_output_directory(const std::string& directory, OutputDirectoryUse use, const SceneSpec& scene,
                              long long step) {
  if (use == OutputDirectoryUse::fresh || !fs::is_directory(directory)) return;
  for (const auto& entry : fs::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || !is_run_file(name)) continue;
    std::smatch m, grid;
    const bool stepped = std::regex_match(name, m, kStepFile);
    // A restart keeps what came before its step, and every checkpoint; the
    // continued run writes the snapshots and grids after it again.
    const bool later = (stepped && m[1] != "checkpoint" && std::stoll(m[2]) > step) ||
                       (std::regex_match(name, grid, kGridFile) && std::stoll(grid[1]) > step);
    const bool temporary = stepped ? m[4].matched : name.find(".tmp") != std::string::npos;
    if (use == OutputDirectoryUse::overwrite || later || temporary) remove_file(entry.path());
  }
  const std::string mixing = mixing_log_name(scene);
  if (use == OutputDirectoryUse::overwrite) {
    if (!mixing.empty() && fs::exists(fs::path(directory) / mixing)) remove_file(fs::path(directory) / mixing);
    return;
  }
  keep_rows_up_to(fs::path(directory) / "timeseries.csv", 0, step);
  keep_rows_up_to(fs::path(directory) / "removed.csv", 1, step);
  keep_rows_up_to(fs::path(directory) / "inlets.csv", 0, step);
  if (!mixing.empty()) keep_rows_up_to(fs::path(directory) / mixing, 1, step);
  for (const FlowSpec& f : scene.measurements.flows) keep_rows_up_to(fs::path(directory) / ("flow_" + f.name + ".csv"), 1, step);
  for (const AverageSpec& a : scene.measurements.averages)
    keep_rows_up_to(fs::path(directory) / ("average_" + a.name + ".csv"), 1, step);
}

}  // namespace gs
