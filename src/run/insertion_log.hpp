#pragma once
// The record of a run's insertion (docs/OUTPUT.md): one row per inlet batch
// in <output>/inlets.csv, and a warning in the run log when a batch could not
// place every particle due. Every rank holds the same records (insertion is
// computed alike everywhere); rank 0 writes them.
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "comm/transport.hpp"
#include "core/insertion_state.hpp"
#include "scene/scene.hpp"

namespace gs {

class InsertionLog {
 public:
  using Log = std::function<void(const std::string& line)>;  // a line for the run log
  InsertionLog(const SceneSpec& scene, const std::string& directory, Transport& transport);
  // Collective: appends the rows; a failure to write stops every rank.
  void write(const std::vector<InsertionRecord>& records, const Log& log);

 private:
  const SceneSpec& scene_;
  std::string path_;
  Transport& transport_;
  std::vector<int> warned_;  // per inlet: shortfall warnings logged so far
};

}  // namespace gs
