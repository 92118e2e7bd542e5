#include "scene/scene_edits.hpp"

#include <yaml-cpp/yaml.h>

#include <map>
#include <utility>

#include "scene/scene_yaml.hpp"

namespace gs {
namespace {

using Leaves = std::vector<std::pair<std::string, std::string>>;  // key path, value; in document order

bool is_scalar_list(const YAML::Node& n) {
  if (!n.IsSequence()) return false;
  for (const YAML::Node& item : n)
    if (!item.IsScalar()) return false;
  return true;
}

// "[1, 2, 3]" for a list of scalars, the scalar itself, "~" for null.
std::string value_text(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  if (n.IsNull()) return "~";
  std::string s = "[";
  bool first = true;
  for (const YAML::Node& item : n) {
    s += (first ? "" : ", ") + item.Scalar();
    first = false;
  }
  return s + "]";
}

void flatten(const YAML::Node& n, const std::string& path, Leaves& out) {
  if (n.IsMap()) {
    for (const auto& kv : n) {
      const std::string key = kv.first.Scalar();
      flatten(kv.second, path.empty() ? key : path + "." + key, out);
    }
    if (n.size() == 0) out.emplace_back(path, "{}");
  } else if (n.IsSequence() && !is_scalar_list(n)) {
    for (std::size_t k = 0; k < n.size(); ++k) flatten(n[k], path + "[" + std::to_string(k) + "]", out);
  } else {
    out.emplace_back(path, value_text(n));
  }
}

bool leaves_of(const std::string& text, Leaves& out) {
  try {
    flatten(YAML::Load(text), "", out);
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

}  // namespace

std::vector<std::string> scene_differences(const std::string& before, const std::string& after) {
  Leaves old_leaves, new_leaves;
  if (!leaves_of(before, old_leaves)) return {"the checkpoint's scene text is not YAML"};
  if (!leaves_of(after, new_leaves)) return {"the scene text is not YAML"};
  std::map<std::string, std::string> old_values(old_leaves.begin(), old_leaves.end());
  std::vector<std::string> lines;
  using scene_yaml::cut;
  for (const auto& [path, value] : new_leaves) {
    const auto it = old_values.find(path);
    if (it == old_values.end()) {
      lines.push_back("added " + path + ": " + cut(value));
      continue;
    }
    if (it->second != value) lines.push_back("changed " + path + ": " + cut(it->second) + " -> " + cut(value));
    old_values.erase(it);
  }
  for (const auto& [path, value] : old_leaves)
    if (old_values.count(path)) lines.push_back("removed " + path + ": " + cut(value));
  return lines;
}

}  // namespace gs
