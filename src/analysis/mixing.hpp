#pragma once
// In-situ mixing analysis (docs/MIXING.md): numerical thief samples on
// concentric rings, then the Lacey index and the relative standard deviation
// of the tracer concentration over the samples (seed paper, Eqs. 13-15).
#include <cstdint>
#include <vector>

#include "scene/mixing_spec.hpp"
#include "core/vec3.hpp"

namespace gs {

struct ParticleSnapshot;

// One sample cylinder: its axis at (x, y), on ring `ring`.
struct SampleSite {
  double x = 0, y = 0;
  int ring = 0;
};

// The sample cylinders of a SampleSpec, ring by ring, and which sample (if
// any) holds a point: sample (site s, layer l) has index s * layers + l.
// Samples never overlap (sample_layout_problem is empty), so a point lies in
// at most one.
class SampleLayout {
 public:
  explicit SampleLayout(const SampleSpec& spec);  // throws std::invalid_argument on a bad spec

  const SampleSpec& spec() const { return spec_; }
  const std::vector<SampleSite>& sites() const { return sites_; }
  int sample_count() const { return int(sites_.size()) * spec_.layers; }
  int ring_count() const { return int(ring_first_.size()); }
  int samples_on_ring(int ring) const { return ring_size_[std::size_t(ring)]; }
  // Index of the sample whose closed cylinder holds the point, or -1.
  int locate(double x, double y, double z) const;

 private:
  SampleSpec spec_;
  std::vector<SampleSite> sites_;
  std::vector<int> ring_first_, ring_size_;  // per ring: index of its first site, number of sites
};

// What one sample holds. Tallies add: tallies of disjoint particle sets (the
// ranks of a run) sum to the tally of their union.
struct SampleTally {
  long long particles = 0;
  long long tracers = 0;      // particles carrying the tracer marker
  double mass = 0;            // [kg]
  double tracer_mass = 0;     // [kg]
};

// Sorts every particle (by its centre) into the sample holding it.
std::vector<SampleTally> tally_samples(const SampleLayout& layout, const std::vector<Vec3d>& position,
                                       const std::vector<float>& mass, const std::vector<std::uint8_t>& marker,
                                       int tracer_marker);
std::vector<SampleTally> tally_samples(const SampleLayout& layout, const ParticleSnapshot& snapshot,
                                       int tracer_marker);

// The mixing state at one time. Statistics that are undefined (fewer than two
// samples count, p = 0 or 1, or one particle per sample) are NaN.
struct MixingResult {
  double time = 0;                 // [s], from the snapshot
  long long step = 0;
  double lacey = 0;                // M = (s0^2 - s^2) / (s0^2 - sr^2), Eq. 13
  double rsd = 0;                  // s / mean concentration, Eq. 15
  double one_minus_rsd = 0;
  double std_dev = 0;              // s over the counted samples, Eq. 14
  double mean_concentration = 0;   // mean of the counted samples' concentrations (Eq. 14's mean)
  double concentration = 0;        // p: tracer fraction of all particles in the counted samples
  double particles_per_sample = 0; // n: mean particle count of the counted samples
  int samples = 0;                 // counted samples (m_S)
  int samples_total = 0;           // all sample cylinders
  long long min_count = 0;         // the fewest particles a sample needed to count
};

// Eqs. 13-15 over the samples that pass the minimum-count rule of `spec`.
MixingResult mixing_statistics(const std::vector<SampleTally>& tallies, const MixingSpec& spec);

// Samples `snapshot` as `spec` says and returns the statistics (time and step
// from the snapshot). Call it on the whole bed: every rank's particles.
MixingResult evaluate_mixing(const MixingSpec& spec, const ParticleSnapshot& snapshot);

}  // namespace gs
