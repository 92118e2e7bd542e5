#include "io/csv_log.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/text_file.hpp"

namespace gs {
namespace {

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) out.push_back(field);
  return out;
}

}  // namespace

CsvLog::CsvLog(std::string path, std::string header) : path_(std::move(path)), header_(std::move(header)) {
  std::string first_line;
  {
    std::ifstream in(path_);
    if (in) std::getline(in, first_line);
  }
  if (first_line.empty()) {
    write_text_file(path_, header_ + "\n");
  } else if (first_line != header_) {
    throw std::runtime_error(path_ + ": exists but is not this measurement's log (first line '" +
                             first_line.substr(0, 80) + "'); move it away or rename the measurement");
  }
}

void CsvLog::append(const std::vector<std::string>& rows) {
  TextFile out(path_, "a");
  for (const std::string& row : rows) out.printf("%s\n", row.c_str());
  out.close();
}

std::vector<std::vector<std::string>> CsvLog::last_rows() const {
  std::ifstream in(path_);
  std::string line;
  std::getline(in, line);  // the header, checked on opening
  std::vector<std::vector<std::string>> last;
  std::string last_step;
  while (std::getline(in, line)) {
    std::vector<std::string> f = fields_of(line);
    if (f.size() < 2) continue;
    if (f[1] != last_step) last.clear();
    last_step = f[1];
    last.push_back(std::move(f));
  }
  return last;
}

}  // namespace gs
