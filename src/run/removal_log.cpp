#include "run/removal_log.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "io/text_file.hpp"

namespace gs {
namespace {

// A name as one CSV field: quoted (quotes doubled) when it holds a comma, a
// quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The fields of one CSV line, quotes undone.
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      out.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

constexpr std::size_t kColumns = 9;

}  // namespace

const char* RemovalLog::header() { return "time,step,outlet,material,marker,count,mass,outlet_count,outlet_mass"; }

RemovalLog::RemovalLog(std::string path, std::vector<std::string> exits, std::vector<std::string> materials, double dt)
    : path_(std::move(path)), exits_(std::move(exits)), materials_(std::move(materials)), dt_(dt),
      count_(exits_.size(), 0), mass_(exits_.size(), 0.0) {
  read_totals();
  file_ = open_for_writing(path_, "a");
  if (std::ftell(file_) == 0) {
    std::fprintf(file_, "%s\n", header());
    flush_checked(file_, path_);
  }
}

RemovalLog::~RemovalLog() {
  if (file_) std::fclose(file_);
}

// The totals are the running sums the file already holds: read back from
// their %.17g text they are the same doubles, so a continued run writes the
// same totals as one that never stopped.
void RemovalLog::read_totals() {
  std::ifstream in(path_);
  std::string line;
  if (!in || !std::getline(in, line) || line.empty()) return;
  if (line != header())
    throw std::runtime_error(path_ + ": exists but is not a removal log (first line '" + line.substr(0, 80) +
                             "'); move it away");
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != kColumns) throw std::runtime_error(path_ + ": a row has " + std::to_string(f.size()) +
                                                       " fields, " + std::to_string(kColumns) + " expected: " + line);
    const auto at = std::find(exits_.begin(), exits_.end(), f[2]);
    if (at == exits_.end())
      throw std::runtime_error(path_ + ": a row names the exit '" + f[2] + "', which the scene does not have");
    const std::size_t e = std::size_t(at - exits_.begin());
    count_[e] = std::strtoll(f[7].c_str(), nullptr, 10);
    mass_[e] = std::strtod(f[8].c_str(), nullptr);
  }
}

void RemovalLog::append(std::vector<RemovedParticle> removed) {
  if (removed.empty()) return;
  auto key = [](const RemovedParticle& r) { return std::make_tuple(r.step, r.exit, r.material, r.marker, r.id); };
  std::sort(removed.begin(), removed.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  for (std::size_t first = 0; first < removed.size();) {
    const RemovedParticle& r = removed[first];
    long long count = 0;
    double mass = 0;
    std::size_t k = first;
    for (; k < removed.size() && removed[k].step == r.step && removed[k].exit == r.exit &&
           removed[k].material == r.material && removed[k].marker == r.marker;
         ++k) {
      ++count;
      mass += double(removed[k].mass);
    }
    const std::size_t e = std::size_t(r.exit);
    count_.at(e) += count;
    mass_[e] += mass;
    std::fprintf(file_, "%.17g,%lld,%s,%s,%d,%lld,%.17g,%lld,%.17g\n", double(r.step) * dt_, r.step,
                 csv_field(exits_[e]).c_str(), csv_field(materials_.at(r.material)).c_str(), int(r.marker), count,
                 mass, count_[e], mass_[e]);
    first = k;
  }
  flush_checked(file_, path_);
}

long long RemovalLog::total_count() const {
  long long n = 0;
  for (long long c : count_) n += c;
  return n;
}

}  // namespace gs
