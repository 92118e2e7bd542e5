#pragma once
// Checked access to a YAML scene for the scene loader: every value carries its
// file, line and key path, so every error can say exactly where it is.
#include <yaml-cpp/yaml.h>

#include <sstream>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace gs::scene_yaml {

// A YAML value and where it came from.
struct Val {
  YAML::Node node;
  std::string path;  // key path, e.g. particles[2].random_fill.radius
  int line = 1;      // 1-based line of the key (or of the list item)
  const std::string* source = nullptr;
  bool present() const { return node.IsDefined(); }
};

// "<source>:<line>: <path>: <what>", how every error and warning begins.
std::string located(const Val& v, const std::string& what);
// Throws SceneError(located(v, what)).
[[noreturn]] void fail(const Val& v, const std::string& what);

template <class T>
std::string str(const T& x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}
std::string str(const Vec3d& v);
// Text from the scene or a library message, cut to about `keep` characters
// when longer, so that an error never echoes a huge value in full.
constexpr std::size_t kEchoLength = 80;
std::string cut(const std::string& s, std::size_t keep = kEchoLength);
// A value from the scene as a message echoes it: 'value', cut.
std::string quoted(const std::string& s);
std::string join(const std::vector<std::string>& names);
int line_of(const YAML::Node& n, int fallback);

// A YAML map whose keys were checked against the allowed ones: unknown or
// repeated keys are errors.
class Map {
 public:
  Map(const Val& v, const std::vector<std::string>& allowed);

  const Val& self() const { return self_; }
  bool has(const std::string& key) const;
  Val opt(const std::string& key) const;  // absent: undefined node located at the map
  Val get(const std::string& key) const;  // absent: error
  // The one key of `choices` that is present; error when none or several are.
  std::string one_of(const std::vector<std::string>& choices) const;

 private:
  Val self_;
  std::vector<std::string> keys_;
  std::vector<Val> fields_;
};

double number(const Val& v);       // finite number
double positive(const Val& v);     // > 0
double nonnegative(const Val& v);  // >= 0
long long integer(const Val& v, long long lo, long long hi);
bool boolean(const Val& v);
std::string text(const Val& v);  // non-empty scalar
std::string choice(const Val& v, const std::vector<std::string>& allowed);
Vec3d vec3(const Val& v);         // [x, y, z]
Vec3d unit_vector(const Val& v);  // non-zero [x, y, z], normalised

double number_or(const Map& m, const std::string& key, double fallback, double (*read)(const Val&));
Vec3d vec3_or(const Map& m, const std::string& key, const Vec3d& fallback);

// Corners of a {min, max} box; min < max on every axis.
void box_corners(const Map& m, Vec3d& lo, Vec3d& hi);

std::string describe(const YAML::Node& n);

// The one document of a scene text; a second document after `---`, or a
// specific tag (!name, !!type) anywhere, is an error at its line.
YAML::Node load_document(const std::string& yaml_text, const std::string& source);

// Calls f(item, index) for each item of a list.
template <class F>
void for_each_item(const Val& v, F&& f) {
  if (!v.node.IsSequence()) fail(v, "expected a list, got " + describe(v.node));
  std::size_t i = 0;
  for (auto it = v.node.begin(); it != v.node.end(); ++it, ++i)
    f(Val{*it, v.path + "[" + std::to_string(i) + "]", line_of(*it, v.line), v.source}, i);
}

}  // namespace gs::scene_yaml
