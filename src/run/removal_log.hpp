#pragma once
// removed.csv: what left the run through its exits (outlets and open faces
// of the domain, scene/outlets.hpp), one row per step, exit, material and
// marker that removed anything, with running totals per exit, so that a
// discharge rate is the slope of `outlet_mass` over `time` (docs/OUTPUT.md).
// The rows depend only on the removed particles, not on which rank removed
// them: masses are summed in id order, totals in row order.
#include <cstdio>
#include <string>
#include <vector>

#include "engine/particle_removal.hpp"

namespace gs {

class RemovalLog {
 public:
  static const char* header();

  // Appends to `path`. A new or empty file gets the header first; an existing
  // one must start with it (a run continued from a checkpoint adds to its
  // log), and its last row of each exit gives that exit's totals so far.
  // `exits`: Exits::names; `materials`: the scene's material names; `dt`:
  // the time step (a row's time is its step times dt, as the run's).
  RemovalLog(std::string path, std::vector<std::string> exits, std::vector<std::string> materials, double dt);
  ~RemovalLog();
  RemovalLog(const RemovalLog&) = delete;
  RemovalLog& operator=(const RemovalLog&) = delete;

  // Writes the rows of `removed` (every rank's, in any order) and flushes
  // them (throws std::runtime_error naming the file when it cannot).
  void append(std::vector<RemovedParticle> removed);

  long long total_count() const;  // removed through every exit so far

 private:
  void read_totals();

  std::string path_;
  std::vector<std::string> exits_, materials_;
  double dt_;
  std::vector<long long> count_;  // per exit, since t = 0
  std::vector<double> mass_;
  std::FILE* file_ = nullptr;
};

}  // namespace gs
