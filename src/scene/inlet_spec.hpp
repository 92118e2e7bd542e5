#pragma once
// An inlet: a region that particles are inserted into during a run, at a rate
// in count or mass per second, or up to a total (docs/SCENES.md, `inlets`).
#include <cstdint>
#include <limits>
#include <string>

#include "scene/fill_region.hpp"
#include "scene/particle_sets.hpp"

namespace gs {

struct InletSpec {
  std::string name;      // for messages and the inlets.csv record
  std::string key;       // where it was given: "<file>:<line>: inlets[i]", for run-time warnings
  ParticleTemplate tmpl;  // material, velocity, angular velocity, marker
  double velocity_spread = 0;  // each velocity component gets a uniform extra in [-spread, spread] [m/s]
  FillRegion region;
  SizeSpec size;         // classes as count fractions (mass fractions are converted when read)
  enum class Amount { count, mass };
  Amount rate_of = Amount::count;  // what `rate` counts
  double rate = 0;                 // per second; 0: no rate, the whole total is due at `start`
  Amount total_of = Amount::count;  // what `total` counts
  double total = std::numeric_limits<double>::infinity();  // stop once this much is in
  double start = 0;                                         // [s]
  double stop = std::numeric_limits<double>::infinity();   // no insertion after this time [s]
  long long interval_steps = 100;  // steps between batches (the loader rounds `interval` to steps)
  std::uint64_t seed = 0;
  int attempts = 20;  // positions tried per particle and batch
};

}  // namespace gs
