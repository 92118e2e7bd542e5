#include "scene/scene_yaml.hpp"

#include <algorithm>
#include <cmath>

namespace gs::scene_yaml {

std::string located(const Val& v, const std::string& what) {
  return *v.source + ":" + std::to_string(v.line) + ": " + (v.path.empty() ? "scene" : cut(v.path, 2 * kEchoLength)) + ": " + what;
}

void fail(const Val& v, const std::string& what) { throw SceneError(located(v, what)); }

std::string str(const Vec3d& v) { return "[" + str(v.x) + ", " + str(v.y) + ", " + str(v.z) + "]"; }

std::string cut(const std::string& s, std::size_t keep) {
  if (s.size() <= keep + 24) return s;  // cutting would save less than the note costs
  return s.substr(0, keep) + "... (" + std::to_string(s.size()) + " characters)";
}

std::string quoted(const std::string& s) { return "'" + cut(s) + "'"; }

std::string describe(const YAML::Node& n) {
  if (n.IsScalar()) return quoted(n.Scalar());
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  return "nothing";
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

int line_of(const YAML::Node& n, int fallback) {
  const YAML::Mark m = n.Mark();
  return m.is_null() ? fallback : m.line + 1;
}

// ---- documents and tags ------------------------------------------------------

namespace {

// "?" marks a plain scalar or an untagged collection, "!" a quoted scalar:
// both non-specific. Anything else (!custom, !!str) is a tag the loader
// would otherwise ignore without a word.
void refuse_tags(const YAML::Node& n, const std::string& source, int fallback_line) {
  const int line = line_of(n, fallback_line);
  const std::string& tag = n.Tag();
  if (!tag.empty() && tag != "?" && tag != "!")
    throw SceneError(source + ":" + std::to_string(line) + ": yaml: the tag " + quoted(tag) +
                     " is not supported; scenes use plain YAML values without tags");
  if (n.IsSequence())
    for (const YAML::Node& item : n) refuse_tags(item, source, line);
  if (n.IsMap())
    for (auto it = n.begin(); it != n.end(); ++it) {
      refuse_tags(it->first, source, line);
      refuse_tags(it->second, source, line_of(it->first, line));
    }
}

}  // namespace

YAML::Node load_document(const std::string& yaml_text, const std::string& source) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(yaml_text);
  } catch (const YAML::Exception& e) {
    throw SceneError(source + ":" + std::to_string(std::max(1, e.mark.line + 1)) + ": yaml syntax: " + cut(e.msg));
  }
  if (documents.empty()) return YAML::Node();  // an empty file: the caller reports the missing keys
  if (documents.size() > 1)
    throw SceneError(source + ":" + std::to_string(line_of(documents[1], 1)) + ": yaml: a second document (after " +
                     "'---') is not allowed; a scene file holds one document");
  refuse_tags(documents[0], source, 1);
  return documents[0];
}

// ---- Map -------------------------------------------------------------------

Map::Map(const Val& v, const std::vector<std::string>& allowed) : self_(v) {
  if (!v.node.IsMap()) fail(v, "expected a map with keys {" + join(allowed) + "}, got " + describe(v.node));
  for (auto it = v.node.begin(); it != v.node.end(); ++it) {
    const int line = line_of(it->first, v.line);
    if (!it->first.IsScalar()) fail({it->first, v.path, line, v.source}, "a key must be a plain name");
    const std::string key = it->first.Scalar();
    const Val field{it->second, v.path.empty() ? key : v.path + "." + key, line, v.source};
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      fail(field, "unknown key " + quoted(key) + "; allowed here: " + join(allowed));
    // yaml-cpp keeps repeated keys silently; a repeat is almost always a slip.
    if (has(key)) fail(field, "key " + quoted(key) + " is given twice");
    keys_.push_back(key);
    fields_.push_back(field);
  }
}

bool Map::has(const std::string& key) const { return std::find(keys_.begin(), keys_.end(), key) != keys_.end(); }

Val Map::opt(const std::string& key) const {
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return fields_[i];
  return {YAML::Node(YAML::NodeType::Undefined), self_.path.empty() ? key : self_.path + "." + key, self_.line,
          self_.source};
}

Val Map::get(const std::string& key) const {
  Val v = opt(key);
  if (!v.present()) fail(self_, "missing required key '" + key + "'");
  return v;
}

std::string Map::one_of(const std::vector<std::string>& choices) const {
  std::vector<std::string> found;
  for (const auto& c : choices)
    if (has(c)) found.push_back(c);
  if (found.size() != 1) fail(self_, "needs exactly one of {" + join(choices) + "}, got {" + join(found) + "}");
  return found[0];
}

// ---- scalars and vectors ----------------------------------------------------

double number(const Val& v) {
  double x = 0;
  if (!v.node.IsScalar() || !YAML::convert<double>::decode(v.node, x) || !std::isfinite(x))
    fail(v, "expected a finite number, got " + describe(v.node));
  return x;
}

double positive(const Val& v) {
  const double x = number(v);
  if (!(x > 0)) fail(v, "must be > 0, got " + str(x));
  return x;
}

double nonnegative(const Val& v) {
  const double x = number(v);
  if (x < 0) fail(v, "must be >= 0, got " + str(x));
  return x;
}

long long integer(const Val& v, long long lo, long long hi) {
  long long x = 0;
  if (!v.node.IsScalar() || !YAML::convert<long long>::decode(v.node, x))
    fail(v, "expected an integer, got " + describe(v.node));
  if (x < lo || x > hi) fail(v, "must lie in [" + str(lo) + ", " + str(hi) + "], got " + str(x));
  return x;
}

bool boolean(const Val& v) {
  bool b = false;
  if (!v.node.IsScalar() || !YAML::convert<bool>::decode(v.node, b))
    fail(v, "expected true or false, got " + describe(v.node));
  return b;
}

std::string text(const Val& v) {
  if (!v.node.IsScalar() || v.node.Scalar().empty()) fail(v, "expected a name, got " + describe(v.node));
  return v.node.Scalar();
}

std::string choice(const Val& v, const std::vector<std::string>& allowed) {
  const std::string s = text(v);
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
    fail(v, quoted(s) + " is not one of {" + join(allowed) + "}");
  return s;
}

Vec3d vec3(const Val& v) {
  if (!v.node.IsSequence() || v.node.size() != 3) fail(v, "expected a list of 3 numbers, got " + describe(v.node));
  double c[3];
  for_each_item(v, [&](const Val& item, std::size_t i) { c[i] = number(item); });
  return Vec3d(c[0], c[1], c[2]);
}

Vec3d unit_vector(const Val& v) {
  const Vec3d a = vec3(v);
  const double n = norm(a);
  if (!(n > 0)) fail(v, "the direction must not be the zero vector");
  return a * (1.0 / n);
}

double number_or(const Map& m, const std::string& key, double fallback, double (*read)(const Val&)) {
  const Val v = m.opt(key);
  return v.present() ? read(v) : fallback;
}

Vec3d vec3_or(const Map& m, const std::string& key, const Vec3d& fallback) {
  const Val v = m.opt(key);
  return v.present() ? vec3(v) : fallback;
}

void box_corners(const Map& m, Vec3d& lo, Vec3d& hi) {
  lo = vec3(m.get("min"));
  hi = vec3(m.get("max"));
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    fail(m.self(), "min " + str(lo) + " must be below max " + str(hi) + " on every axis");
}

}  // namespace gs::scene_yaml
