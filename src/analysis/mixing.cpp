#include "analysis/mixing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/particle_snapshot.hpp"

namespace gs {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();



}  // namespace

SampleLayout::SampleLayout(const SampleSpec& spec) : spec_(spec) {
  const std::string problem = sample_layout_problem(spec);
  if (!problem.empty()) throw std::invalid_argument("mixing samples: " + problem);
  for (std::size_t k = 0; k < spec.ring_radii.size(); ++k) {
    const double r = spec.ring_radii[k];
    const int n = ring_sample_count(r, spec.spacing);
    ring_first_.push_back(int(sites_.size()));
    ring_size_.push_back(n);
    for (int j = 0; j < n; ++j) {
      const double angle = 2 * kPi * j / n;
      sites_.push_back({spec.center_x + r * std::cos(angle), spec.center_y + r * std::sin(angle), int(k)});
    }
  }
}

int SampleLayout::locate(double x, double y, double z) const {
  if (z < spec_.bottom || z > spec_.bottom + spec_.height) return -1;
  // Layer of z; the top face belongs to the top layer.
  const int layer = std::min(spec_.layers - 1, int((z - spec_.bottom) / spec_.height * spec_.layers));
  const double a = spec_.radius;
  const double dx = x - spec_.center_x, dy = y - spec_.center_y;
  const double rho = std::sqrt(dx * dx + dy * dy);
  // Only rings with |r_k - rho| <= a can hold the point; on such a ring the
  // nearest centre is the one nearest in angle.
  const auto& radii = spec_.ring_radii;
  const double angle = std::atan2(dy, dx);
  for (auto it = std::lower_bound(radii.begin(), radii.end(), rho - a); it != radii.end() && *it <= rho + a; ++it) {
    const std::size_t k = std::size_t(it - radii.begin());
    const int n = ring_size_[k];
    const int j = ((int(std::lround(angle * n / (2 * kPi))) % n) + n) % n;
    const SampleSite& site = sites_[std::size_t(ring_first_[k] + j)];
    const double ex = x - site.x, ey = y - site.y;
    if (ex * ex + ey * ey <= a * a) return (ring_first_[k] + j) * spec_.layers + layer;
  }
  return -1;
}

std::vector<SampleTally> tally_samples(const SampleLayout& layout, const std::vector<Vec3d>& position,
                                       const std::vector<float>& mass, const std::vector<std::uint8_t>& marker,
                                       int tracer_marker) {
  if (mass.size() != position.size() || marker.size() != position.size())
    throw std::invalid_argument("tally_samples: position, mass and marker differ in length");
  std::vector<SampleTally> tallies(std::size_t(layout.sample_count()));
  for (std::size_t i = 0; i < position.size(); ++i) {
    const int s = layout.locate(position[i].x, position[i].y, position[i].z);
    if (s < 0) continue;
    SampleTally& t = tallies[std::size_t(s)];
    const bool tracer = marker[i] == tracer_marker;
    t.particles += 1;
    t.tracers += tracer;
    t.mass += mass[i];
    if (tracer) t.tracer_mass += mass[i];
  }
  return tallies;
}

std::vector<SampleTally> tally_samples(const SampleLayout& layout, const ParticleSnapshot& snapshot,
                                       int tracer_marker) {
  return tally_samples(layout, snapshot.position, snapshot.mass, snapshot.marker, tracer_marker);
}

MixingResult mixing_statistics(const std::vector<SampleTally>& tallies, const MixingSpec& spec) {
  MixingResult r;
  r.samples_total = int(tallies.size());

  // Minimum-count rule: a sample cut by the bed surface or a blade holds few
  // particles, and its concentration scatters far more than p(1-p)/n.
  std::vector<long long> counts;
  for (const auto& t : tallies)
    if (t.particles > 0) counts.push_back(t.particles);
  double median = 0;
  if (!counts.empty()) {
    std::sort(counts.begin(), counts.end());
    const std::size_t h = counts.size() / 2;
    median = counts.size() % 2 ? double(counts[h]) : 0.5 * double(counts[h - 1] + counts[h]);
  }
  const auto fill = static_cast<long long>(std::ceil(spec.min_fill * median - 1e-9));
  r.min_count = std::max<long long>({1, spec.min_particles, fill});

  const bool by_mass = spec.basis == ConcentrationBasis::mass;
  double sum_x = 0, particles = 0, amount = 0, tracer_amount = 0;
  std::vector<double> x;
  for (const auto& t : tallies) {
    if (t.particles < r.min_count) continue;
    const double total = by_mass ? t.mass : double(t.particles);
    const double tracer = by_mass ? t.tracer_mass : double(t.tracers);
    x.push_back(tracer / total);
    sum_x += x.back();
    particles += double(t.particles);
    amount += total;
    tracer_amount += tracer;
  }
  r.samples = int(x.size());
  if (r.samples == 0) {
    r.lacey = r.rsd = r.one_minus_rsd = r.std_dev = r.mean_concentration = r.concentration = kNaN;
    return r;
  }
  r.particles_per_sample = particles / r.samples;
  r.concentration = tracer_amount / amount;
  r.mean_concentration = sum_x / r.samples;

  // Eq. 14: the sample standard deviation about the mean of the samples.
  double squares = 0;
  for (double xi : x) squares += (xi - r.mean_concentration) * (xi - r.mean_concentration);
  r.std_dev = r.samples > 1 ? std::sqrt(squares / (r.samples - 1)) : kNaN;

  // Eq. 13 with Lacey's bounds: s0^2 fully segregated, sr^2 random mixture of n-particle samples.
  const double p = r.concentration, n = r.particles_per_sample;
  const double s0_sq = p * (1 - p);
  const double sr_sq = p * (1 - p) / n;
  const double s_sq = r.std_dev * r.std_dev;
  r.lacey = s0_sq - sr_sq > 0 ? (s0_sq - s_sq) / (s0_sq - sr_sq) : kNaN;

  // Eq. 15.
  r.rsd = r.mean_concentration > 0 ? r.std_dev / r.mean_concentration : kNaN;
  r.one_minus_rsd = 1 - r.rsd;
  return r;
}

MixingResult evaluate_mixing(const MixingSpec& spec, const ParticleSnapshot& snapshot) {
  const SampleLayout layout(spec.samples);
  MixingResult r = mixing_statistics(tally_samples(layout, snapshot, spec.tracer_marker), spec);
  r.time = snapshot.time;
  r.step = snapshot.step;
  return r;
}

}  // namespace gs
