#include "io/h5_describe.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "io/checkpoint.hpp"
#include "io/fnv1a.hpp"
#include "io/h5_io.hpp"
#include "io/state_digest.hpp"

namespace gs {
namespace {

std::string format(const char* fmt, double a) {
  char s[64];
  std::snprintf(s, sizeof(s), fmt, a);
  return s;
}

std::string vec_text(const Vec3d& v) {
  return "[" + format("%.6g", v.x) + ", " + format("%.6g", v.y) + ", " + format("%.6g", v.z) + "]";
}

void line(std::ostream& out, const char* key, const std::string& value) {
  char label[24];
  std::snprintf(label, sizeof(label), "%-15s", (std::string(key) + ":").c_str());
  out << label << value << "\n";
}

void describe_particles(std::ostream& out, const h5::File& f, std::int64_t n) {
  line(out, "particles", std::to_string(n));
  std::string fields;
  for (const std::string& name : h5::list_group(f, "particles")) fields += (fields.empty() ? "" : " ") + name;
  line(out, "fields", fields);
  if (n <= 0 || !h5::exists(f, "particles/position")) return;
  const std::vector<Vec3d> x = h5::read_vec3(f, "particles/position", hsize_t(n));
  const double inf = std::numeric_limits<double>::infinity();
  Vec3d lo(inf, inf, inf), hi(-inf, -inf, -inf);
  for (const Vec3d& p : x) {
    lo = Vec3d(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
    hi = Vec3d(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
  }
  line(out, "bounding box", vec_text(lo) + " to " + vec_text(hi) + " m (particle centres)");
  if (!h5::exists(f, "particles/radius")) return;
  const std::vector<float> r = h5::read_array<float>(f, "particles/radius", {hsize_t(n)});
  const auto [rmin, rmax] = std::minmax_element(r.begin(), r.end());
  line(out, "radius", format("%.6g", *rmin) + " to " + format("%.6g", *rmax) + " m");
}

void describe_walls(std::ostream& out, const h5::File& f) {
  if (!h5::exists(f, "walls/kind")) return;
  const std::vector<hsize_t> dims = h5::dims_of(f, "walls/kind");
  const auto kind = h5::read_array<std::int32_t>(f, "walls/kind", dims);
  int count[3] = {0, 0, 0};
  for (std::int32_t k : kind)
    if (k >= 0 && k < 3) ++count[k];
  line(out, "walls", std::to_string(kind.size()) + " (" + std::to_string(count[0]) + " plane, " +
                         std::to_string(count[1]) + " disk, " + std::to_string(count[2]) + " cylinder)");
}

bool has_rows(const h5::File& f, const std::string& path) {
  const std::vector<hsize_t> dims = h5::dims_of(f, path);
  return !dims.empty() && dims[0] > 0;
}

void describe_checkpoint(std::ostream& out, const h5::File& f) {
  const auto slots = h5::read_attribute<std::int32_t>(f, "history", "slots");
  line(out, "history", std::to_string(slots) + " slots per particle, tangential springs " +
                           (has_rows(f, "history/tangential") ? "yes" : "no") + ", rolling springs " +
                           (has_rows(f, "history/rolling") ? "yes" : "no"));
  const auto ranks = h5::read_attribute<std::int32_t>(f, "decomposition", "rank_count");
  const auto axis = h5::read_attribute<std::int32_t>(f, "decomposition", "axis");
  const auto cuts = h5::read_array<double>(f, "decomposition/cuts", h5::dims_of(f, "decomposition/cuts"));
  std::string cut_text;
  for (double c : cuts) cut_text += (cut_text.empty() ? "" : ", ") + format("%.6g", c);
  const std::string layout = axis >= 0 && axis <= 2 ? std::string("slab axis ") + "xyz"[axis] + ", cuts [" + cut_text + "] m"
                                                    : std::string("not slabs");
  line(out, "decomposition", std::to_string(ranks) + " rank(s), " + layout);
}

}  // namespace

H5Description describe_h5(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error(path + ": no such file");
  h5::silence_library_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error(path + " is not an HDF5 file");
  h5::File f = h5::File::open_read_only(path);
  const std::string kind = h5::has_attribute(f, "/", "kind") ? h5::read_string_attribute(f, "/", "kind") : "";
  const bool checkpoint = kind == "grainstorm checkpoint";
  if (!checkpoint && kind != "grainstorm snapshot")
    throw std::runtime_error(path + " is neither a grainstorm snapshot nor a checkpoint");
  std::ostringstream out;
  line(out, "file", path);
  line(out, "kind", std::string(checkpoint ? "checkpoint" : "snapshot") + ", format version " +
                        std::to_string(h5::read_attribute<std::int32_t>(f, "/", "format_version")) +
                        ", written by grainstorm " + h5::read_string_attribute(f, "/", "grainstorm_version"));
  line(out, "time", format("%.9g", h5::read_attribute<double>(f, "/", "time")) + " s, step " +
                        std::to_string(h5::read_attribute<std::int64_t>(f, "/", "step")));
  const auto n = h5::read_row_count(f, "/", "particle_count", "particles/position");
  describe_particles(out, f, n);
  describe_walls(out, f);
  if (checkpoint) describe_checkpoint(out, f);
  line(out, "scene hash", hex64(h5::read_attribute<std::uint64_t>(f, "/", "scene_hash")));
  if (checkpoint)
    line(out, "scene text", h5::exists(f, "scene_text")
                                ? std::to_string(h5::dims_of(f, "scene_text").at(0)) + " bytes (dataset scene_text)"
                                : std::string("not stored (written before 2026-12-05)"));
  if (h5::has_attribute(f, "/", "scene")) {
    const std::string scene = h5::read_string_attribute(f, "/", "scene");
    if (!scene.empty()) line(out, "scene", scene);
  }
  f.close();
  bool damaged = false;
  if (checkpoint) {
    try {
      const Checkpoint c = read_checkpoint(path);
      line(out, "integrity", "complete, checksum matches");
      line(out, "state digest", hex64(state_digest(c.particles, c.history)) + " (every field and spring, by particle id)");
    } catch (const CheckpointError& e) {
      line(out, "integrity", std::string("DAMAGED: ") + e.what());
      damaged = true;
    }
  }
  return {out.str(), damaged};
}

}  // namespace gs
