#pragma once
// A CSV time series that a run appends to, one evaluation at a time, and a
// restart continues (the measurements' logs, docs/OUTPUT.md): every row's
// first two columns are time and step.
#include <string>
#include <vector>

namespace gs {

class CsvLog {
 public:
  // A new or empty file gets `header`; an existing one must start with it
  // (else std::runtime_error naming the file: it is not this log).
  CsvLog(std::string path, std::string header);

  const std::string& path() const { return path_; }
  // Appends `rows` (each without its newline) and flushes; std::runtime_error on failure.
  void append(const std::vector<std::string>& rows);
  // After a restart at `step`: drops the rows of later steps (written by the
  // run that was stopped after its checkpoint) and returns the rows of the
  // last step at or before it, split into fields (empty when none).
  std::vector<std::vector<std::string>> resume(long long step);

 private:
  std::string path_, header_;
};

}  // namespace gs
