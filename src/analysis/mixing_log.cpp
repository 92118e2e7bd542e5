#include "analysis/mixing_log.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <utility>

namespace gs {

namespace {

// %.9g, and "nan" for an undefined statistic whatever the C library prints.
std::string field(double x) {
  if (std::isnan(x)) return "nan";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  return buffer;
}

}  // namespace

const char* MixingLog::header() {
  return "time,step,revolutions,lacey,rsd,one_minus_rsd,samples,particles_per_sample,concentration";
}

MixingLog::MixingLog(std::string path, double revolution_period, double start)
    : path_(std::move(path)), revolution_period_(revolution_period), start_(start) {
  std::string first_line;
  {
    std::ifstream in(path_);
    if (in) std::getline(in, first_line);
  }
  if (first_line.empty()) {
    std::ofstream out(path_, std::ios::trunc);
    out << header() << '\n';
    if (!out.flush()) throw std::runtime_error(path_ + ": cannot write the mixing log");
  } else if (first_line != header()) {
    throw std::runtime_error(path_ + ": exists but is not a mixing log (first line '" + first_line +
                             "'); move it away or choose another analysis.mixing.output");
  }
}

MixingLog::MixingLog(const MixingSpec& spec, const std::string& path)
    : MixingLog(path, spec.revolution_period, spec.start) {}

void MixingLog::append(const MixingResult& r) {
  std::ofstream out(path_, std::ios::app);
  out << field(r.time) << ',' << r.step << ','
      << (revolution_period_ > 0 ? field((r.time - start_) / revolution_period_) : "") << ',' << field(r.lacey)
      << ',' << field(r.rsd) << ',' << field(r.one_minus_rsd) << ',' << r.samples << ','
      << field(r.particles_per_sample) << ',' << field(r.concentration) << '\n';
  if (!out.flush()) throw std::runtime_error(path_ + ": cannot append to the mixing log");
}

}  // namespace gs
