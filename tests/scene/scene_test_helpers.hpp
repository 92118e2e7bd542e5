#pragma once
// What the loader tests share: editing a scene text and checking the error
// the loader gives for it.
#include <gtest/gtest.h>

#include <string>

#include "scene/scene_loader.hpp"

namespace gs::test {

// `text` with the first occurrence of `from` replaced by `to`; a test bug when it has none.
inline std::string edited(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The loader's message for `text` read as `file`, or "(no error)".
inline std::string scene_error_of(const std::string& text, const std::string& file = "scene.yaml") {
  try {
    parse_scene(text, file);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// The error names the file and line, then the key path, then what is wrong.
inline void expect_scene_error(const std::string& text, int line, const std::string& key, const std::string& what,
                               const std::string& file = "scene.yaml") {
  const std::string msg = scene_error_of(text, file);
  const std::string where = file + ":" + std::to_string(line) + ": ";
  EXPECT_EQ(msg.rfind(where, 0), 0u) << "expected " << where << " in: " << msg;
  EXPECT_NE(msg.find(key), std::string::npos) << "expected key '" << key << "' in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
}

}  // namespace gs::test
