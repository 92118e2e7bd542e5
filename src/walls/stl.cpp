#include "walls/stl.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gs {

namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kRecordBytes = 50;

std::string file_stem(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  std::string stem = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = stem.rfind('.');
  return dot == std::string::npos ? stem : stem.substr(0, dot);
}

std::string read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open STL file: " + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw std::runtime_error(path + ": error while reading the STL file");
  return buffer.str();
}

std::uint32_t read_u32_le(const char* p) {
  const auto* u = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t(u[0]) | std::uint32_t(u[1]) << 8 | std::uint32_t(u[2]) << 16 | std::uint32_t(u[3]) << 24;
}

float read_f32_le(const char* p) {
  const std::uint32_t u = read_u32_le(p);
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

void put_u32_le(std::string& out, std::uint32_t u) {
  for (int k = 0; k < 4; ++k) out.push_back(char((u >> (8 * k)) & 0xFFu));
}

void put_f32_le(std::string& out, float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  put_u32_le(out, u);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool starts_with_solid(const std::string& data) {
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  return i + 5 <= data.size() && lower(data.substr(i, 5)) == "solid";
}

bool looks_like_text(const std::string& data) {
  for (unsigned char c : data)
    if (c == 0 || (c < 32 && !std::isspace(c)) || c == 127) return false;
  return true;
}

bool finite(const Vec3d& x) { return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z); }

// Corner positions per facet, before vertices are shared; `where[t]` says
// where facet t is in the file, for messages.
struct Soup {
  std::string name;
  std::vector<Vec3d> corners;  // 3 per facet
  std::vector<std::string> where;
};

Soup parse_binary(const std::string& path, const std::string& data) {
  const std::uint32_t n = read_u32_le(data.data() + kHeaderBytes);
  Soup soup;
  soup.name = file_stem(path);
  soup.corners.reserve(3 * std::size_t(n));
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* record = data.data() + kHeaderBytes + 4 + kRecordBytes * std::size_t(t);
    for (int k = 0; k < 3; ++k) {
      const char* v = record + 12 + 12 * k;  // after the facet normal
      soup.corners.emplace_back(read_f32_le(v), read_f32_le(v + 4), read_f32_le(v + 8));
    }
    soup.where.push_back("facet " + std::to_string(t));
  }
  return soup;
}

// Whitespace-separated words with their line numbers.
class Words {
 public:
  Words(const std::string& path, const std::string& text) : path_(path), in_(text) {}

  bool next(std::string& word) {
    char c;
    while (in_.get(c)) {
      if (c == '\n') ++line_;
      if (!std::isspace(static_cast<unsigned char>(c))) {
        word.assign(1, c);
        while (in_.get(c) && !std::isspace(static_cast<unsigned char>(c))) word.push_back(c);
        if (in_) in_.unget();
        return true;
      }
    }
    return false;
  }
  std::string rest_of_line() {
    std::string rest;
    std::getline(in_, rest);
    ++line_;
    const std::size_t b = rest.find_first_not_of(" \t\r");
    const std::size_t e = rest.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : rest.substr(b, e - b + 1);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_ + ":" + std::to_string(line_) + ": malformed ASCII STL: " + what);
  }
  void expect(const char* keyword) {
    std::string w;
    if (!next(w)) fail(std::string("unexpected end of file, expected '") + keyword + "'");
    if (lower(w) != keyword) fail(std::string("expected '") + keyword + "', got '" + w + "'");
  }
  double number() {
    std::string w;
    if (!next(w)) fail("unexpected end of file, expected a number");
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0') fail("expected a number, got '" + w + "'");
    return v;
  }
  Vec3d vector() {
    const double x = number(), y = number(), z = number();
    return Vec3d(x, y, z);
  }
  int line() const { return line_; }

 private:
  std::string path_;
  std::istringstream in_;
  int line_ = 1;
};

Soup parse_ascii(const std::string& path, const std::string& text) {
  Words words(path, text);
  Soup soup;
  std::string w;
  bool any_solid = false;
  while (words.next(w)) {
    if (lower(w) != "solid") words.fail("expected 'solid', got '" + w + "'");
    const std::string name = words.rest_of_line();
    if (!any_solid) soup.name = name.empty() ? file_stem(path) : name;
    any_solid = true;
    for (;;) {
      if (!words.next(w)) words.fail("unexpected end of file inside a solid (missing 'endsolid')");
      const std::string key = lower(w);
      if (key == "endsolid") {
        words.rest_of_line();  // optional name
        break;
      }
      if (key != "facet") words.fail("expected 'facet' or 'endsolid', got '" + w + "'");
      const int facet_line = words.line();
      words.expect("normal");
      words.vector();  // ignored: the winding defines the orientation
      words.expect("outer");
      words.expect("loop");
      for (int k = 0; k < 3; ++k) {
        if (!words.next(w)) words.fail("unexpected end of file inside a facet");
        if (lower(w) != "vertex")
          words.fail(k == 0 ? "expected 'vertex', got '" + w + "'"
                            : "a facet must have exactly 3 vertices, got " + std::to_string(k) + " then '" + w + "'");
        soup.corners.push_back(words.vector());
      }
      if (!words.next(w)) words.fail("unexpected end of file inside a facet");
      if (lower(w) == "vertex") words.fail("a facet must have exactly 3 vertices, got more");
      if (lower(w) != "endloop") words.fail("expected 'endloop', got '" + w + "'");
      words.expect("endfacet");
      soup.where.push_back("facet " + std::to_string(soup.where.size()) + " (line " + std::to_string(facet_line) + ")");
    }
  }
  if (!any_solid) words.fail("the file is empty");
  return soup;
}

TriangleMesh mesh_from_soup(const std::string& path, const Soup& soup, const StlReadOptions& options) {
  if (soup.where.empty()) throw std::runtime_error(path + ": the STL file has no triangles");
  TriangleMeshBuilder builder(soup.name);
  for (std::size_t t = 0; t < soup.where.size(); ++t) {
    Vec3d x[3];
    for (int k = 0; k < 3; ++k) {
      x[k] = soup.corners[3 * t + k] * options.scale;
      if (!finite(x[k])) throw std::runtime_error(path + ": " + soup.where[t] + " has a NaN or infinite coordinate");
    }
    builder.triangle(x[0], x[1], x[2]);
  }
  TriangleMesh mesh = builder.take();
  if (options.weld_tolerance > 0) weld_vertices(mesh, options.weld_tolerance);
  std::size_t t = 0;
  const std::string problem = find_mesh_problem(mesh, t);
  if (!problem.empty()) {
    std::string message = path + ": " + soup.where[t] + " " + problem;
    if (options.weld_tolerance > 0) message += " (after welding corners closer than " + std::to_string(options.weld_tolerance) + " m)";
    throw std::runtime_error(message);
  }
  return mesh;
}

}  // namespace

TriangleMesh read_stl(const std::string& path, const StlReadOptions& options) {
  if (!(options.scale > 0) || !std::isfinite(options.scale))
    throw std::invalid_argument(path + ": STL scale must be positive and finite");
  if (!(options.weld_tolerance >= 0)) throw std::invalid_argument(path + ": STL weld tolerance must be >= 0");
  const std::string data = read_whole_file(path);
  const std::size_t size = data.size();
  if (size >= kHeaderBytes + 4) {
    const std::uint64_t n = read_u32_le(data.data() + kHeaderBytes);
    const std::uint64_t expected = kHeaderBytes + 4 + kRecordBytes * n;
    if (size == expected) return mesh_from_soup(path, parse_binary(path, data), options);
    if (!(starts_with_solid(data) && looks_like_text(data))) {
      throw std::runtime_error(path + ": truncated or corrupt binary STL: the header announces " + std::to_string(n) +
                               " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                               std::to_string(size) + " bytes");
    }
  } else if (!(starts_with_solid(data) && looks_like_text(data))) {
    throw std::runtime_error(path + ": not an STL file: " + std::to_string(size) +
                             " bytes, too short for a binary STL (84 bytes at least) and not ASCII ('solid ...')");
  }
  return mesh_from_soup(path, parse_ascii(path, data), options);
}

void write_stl(const std::string& path, const TriangleMesh& mesh, StlFormat format) {
  std::string out;
  auto unit_normal = [&](const TriangleIndices& t) {
    const Vec3d& a = mesh.vertices[t[0]];
    const Vec3d n = cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a);
    const double len = norm(n);
    return len > 0 ? n * (1.0 / len) : Vec3d();
  };
  if (format == StlFormat::binary) {
    std::string header = "grainstorm binary STL: " + mesh.name;
    header.resize(kHeaderBytes, ' ');  // does not start with "solid"
    out = header;
    put_u32_le(out, std::uint32_t(mesh.triangles.size()));
    for (const TriangleIndices& t : mesh.triangles) {
      const Vec3d n = unit_normal(t);
      for (double c : {n.x, n.y, n.z}) put_f32_le(out, float(c));
      for (int k = 0; k < 3; ++k) {
        const Vec3d& x = mesh.vertices[t[k]];
        for (double c : {x.x, x.y, x.z}) put_f32_le(out, float(c));
      }
      out.append(2, '\0');  // attribute byte count
    }
  } else {
    const std::string name = mesh.name.empty() ? "mesh" : mesh.name;
    char line[160];
    out = "solid " + name + "\n";
    for (const TriangleIndices& t : mesh.triangles) {
      const Vec3d n = unit_normal(t);
      std::snprintf(line, sizeof line, "  facet normal %.17g %.17g %.17g\n    outer loop\n", n.x, n.y, n.z);
      out += line;
      for (int k = 0; k < 3; ++k) {
        const Vec3d& x = mesh.vertices[t[k]];
        std::snprintf(line, sizeof line, "      vertex %.17g %.17g %.17g\n", x.x, x.y, x.z);
        out += line;
      }
      out += "    endloop\n  endfacet\n";
    }
    out += "endsolid " + name + "\n";
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw std::runtime_error(path + ": cannot write STL file: " + std::strerror(errno));
  file.write(out.data(), std::streamsize(out.size()));
  if (!file) throw std::runtime_error(path + ": error while writing the STL file");
}

}  // namespace gs
