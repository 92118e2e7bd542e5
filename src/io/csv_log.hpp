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
  // The rows of the last step in the file, split into fields (empty when
  // there are none): after a restart, the rows of later steps are gone
  // already (run/output_directory.hpp).
  std::vector<std::vector<std::string>> last_rows() const;

 private:
  std::string path_, header_;
};

}  // namespace gs
