#include "scene/mixing_spec.hpp"

#include <algorithm>
#include <cmath>

#include "scene/number_text.hpp"

namespace gs {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

int ring_sample_count(double r, double spacing) { return std::max(1, int(std::lround(2 * kPi * r / spacing))); }

double sample_radius_for_mass(double mass, double bulk_density, double height) {
  return std::sqrt(mass / (bulk_density * kPi * height));
}

std::vector<double> ring_radii_in_annulus(double inner, double outer, int count) {
  std::vector<double> radii;
  const double width = (outer - inner) / count;
  for (int k = 0; k < count; ++k) radii.push_back(inner + (k + 0.5) * width);
  return radii;
}

std::string sample_layout_problem(const SampleSpec& spec) {
  if (!(spec.radius > 0)) return "the sample radius must be > 0, got " + number_text(spec.radius);
  if (!(spec.height > 0)) return "the sample height must be > 0, got " + number_text(spec.height);
  if (!(spec.layers >= 1)) return "the samples need at least one layer, got " + std::to_string(spec.layers);
  if (!(spec.spacing > 0)) return "the spacing along a ring must be > 0, got " + number_text(spec.spacing);
  if (spec.ring_radii.empty()) return "at least one ring is needed";
  const double a = spec.radius;
  for (std::size_t k = 0; k < spec.ring_radii.size(); ++k) {
    const double r = spec.ring_radii[k];
    if (!(r >= 0)) return "ring radius " + number_text(r) + " must be >= 0";
    // Centres on rings r1 < r2 are at least r2 - r1 apart.
    if (k > 0 && !(r - spec.ring_radii[k - 1] >= 2 * a))
      return "rings " + number_text(spec.ring_radii[k - 1]) + " and " + number_text(r) +
             " must be ascending and at least two sample radii (" + number_text(2 * a) +
             ") apart, or their samples overlap";
    const int n = ring_sample_count(r, spec.spacing);
    const double chord = 2 * r * std::sin(kPi / n);  // between neighbouring centres
    if (n > 1 && !(chord >= 2 * a))
      return "the " + std::to_string(n) + " samples on ring " + number_text(r) + " are " + number_text(chord) +
             " apart, less than two sample radii (" + number_text(2 * a) + "); raise the spacing or shrink the samples";
  }
  return "";
}

}  // namespace gs
