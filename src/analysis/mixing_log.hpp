#pragma once
// The mixing analysis's CSV log: one row per evaluation (docs/MIXING.md).
#include <string>

#include "analysis/mixing.hpp"

namespace gs {

class MixingLog {
 public:
  // Columns of every row, in order.
  static const char* header();

  // Appends to `path`. A new or empty file gets the header first; an existing
  // file must start with this header (a run continued from a checkpoint adds
  // to its log), else std::runtime_error. `revolution_period` > 0 fills the
  // revolutions column with (time - start) / revolution_period; 0 leaves it empty.
  MixingLog(std::string path, double revolution_period = 0, double start = 0);
  MixingLog(const MixingSpec& spec, const std::string& path);

  const std::string& path() const { return path_; }
  // Writes one row and flushes it to the file (throws std::runtime_error on failure).
  void append(const MixingResult& result);

 private:
  std::string path_;
  double revolution_period_ = 0, start_ = 0;
};

}  // namespace gs
