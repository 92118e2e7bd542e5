#pragma once
// What the in-situ mixing analysis samples and how often (docs/MIXING.md):
// plain data, held by SceneSpec and read by analysis/mixing.hpp.
#include <string>
#include <vector>

namespace gs {

// Samples are vertical cylinders (a thief probe's core), all of one radius and
// height, standing on z = bottom, centred at equidistant points on concentric
// circles around the vertical axis through (center_x, center_y) (seed paper,
// Fig. 4). Ring k of radius r_k holds max(1, round(2 pi r_k / spacing))
// samples, so the count per ring is proportional to its circumference.
struct SampleSpec {
  double center_x = 0, center_y = 0;  // the vertical axis the rings go round [m]
  std::vector<double> ring_radii;     // ascending, >= 0 [m]
  double spacing = 0;                 // target arc length between neighbours on a ring [m]
  double radius = 0;                  // sample cylinder radius [m]
  double height = 0;                  // sample cylinder height [m]
  double bottom = 0;                  // z of the cylinder bottoms [m]
  // Each cylinder cut into this many samples of equal height, stacked: in a
  // bed much taller than the blades, a full-height sample counts a lower part
  // turned against an upper one as mixed (docs/MIXER.md).
  int layers = 1;
};

// Which concentration the statistics use: number fraction of tracer particles
// (the seed's choice for its equal spheres) or mass fraction.
enum class ConcentrationBasis { number, mass };

struct MixingSpec {
  SampleSpec samples;
  int tracer_marker = 1;              // particles with this marker are the tracer species
  ConcentrationBasis basis = ConcentrationBasis::number;
  // A sample counts when it holds at least max(min_particles,
  // ceil(min_fill * median particle count of the non-empty samples)).
  int min_particles = 2;
  double min_fill = 0.5;
  double every = 0;                   // simulated seconds between evaluations (> 0)
  double start = 0;                   // simulated time of the first evaluation [s]
  double revolution_period = 0;       // seconds per revolution for the log's revolutions column; 0: none
  std::string output = "mixing.csv";  // CSV log; a relative path lies in output.directory
};

// Samples on a ring of radius r: equidistant, about `spacing` apart along the
// circle; a ring of radius 0 is the single sample on the axis.
int ring_sample_count(double r, double spacing);

// Radius of a sample (one layer's cylinder) of `height` holding `mass` of powder at
// `bulk_density`: m = rho_bulk pi a^2 h.
double sample_radius_for_mass(double mass, double bulk_density, double height);

// Ring radii at the middle of `count` equal-width rings filling the annulus
// inner <= r <= outer: r_k = inner + (k + 1/2) (outer - inner) / count.
std::vector<double> ring_radii_in_annulus(double inner, double outer, int count);

// Why the samples are unusable (an empty string when they are fine): sizes not
// positive, fewer than one layer, radii not ascending, or two sample cylinders
// overlapping.
std::string sample_layout_problem(const SampleSpec& spec);

}  // namespace gs
