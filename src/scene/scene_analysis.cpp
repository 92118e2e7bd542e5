// `analysis:` -> SceneSpec::mixing (docs/SCENES.md, docs/MIXING.md).
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene_sections.hpp"

namespace gs::scene_yaml {

namespace {

const std::vector<std::string> kMixingKeys = {
    "center",        "bottom",      "height",       "rings",         "ring_radii", "spacing",
    "sample_radius", "sample_mass", "bulk_density", "tracer_marker", "basis",      "min_particles",
    "min_fill",      "every",       "start",        "revolution_period", "output",     "layers"};

void read_center(const Val& v, SampleSpec& samples) {
  if (!v.node.IsSequence() || v.node.size() != 2)
    fail(v, "expected a list of 2 numbers [x, y] (the vertical axis of the rings), got " + describe(v.node));
  double c[2];
  for_each_item(v, [&](const Val& item, std::size_t i) { c[i] = number(item); });
  samples.center_x = c[0];
  samples.center_y = c[1];
}

// `rings: {inner_radius, outer_radius, count}` or `ring_radii: [...]`, and the spacing along a ring.
// Returns the ring width of the annulus form (samples must fit in it), 0 for a list.
double read_rings(const Map& m, SampleSpec& samples) {
  if (m.one_of({"rings", "ring_radii"}) == "rings") {
    const Map r(m.get("rings"), {"inner_radius", "outer_radius", "count"});
    const double inner = nonnegative(r.get("inner_radius"));
    const double outer = positive(r.get("outer_radius"));
    if (!(outer > inner))
      fail(r.get("outer_radius"), "must exceed inner_radius " + str(inner) + ", got " + str(outer));
    const int count = int(integer(r.get("count"), 1, 100000));
    samples.ring_radii = ring_radii_in_annulus(inner, outer, count);
    const double width = (outer - inner) / count;
    samples.spacing = number_or(m, "spacing", width, positive);
    return width;
  }
  for_each_item(m.get("ring_radii"), [&](const Val& item, std::size_t i) {
    const double r = nonnegative(item);
    if (i > 0 && !(r > samples.ring_radii.back()))
      fail(item, "ring radii must be ascending; " + str(r) + " follows " + str(samples.ring_radii.back()));
    samples.ring_radii.push_back(r);
  });
  if (samples.ring_radii.empty()) fail(m.get("ring_radii"), "at least one ring radius is needed");
  samples.spacing = positive(m.get("spacing"));
  return 0;
}

// `sample_radius`, or `sample_mass` with `bulk_density` (m = rho_bulk pi a^2 h,
// h the height of one layer).
void read_sample_size(const Map& m, SampleSpec& samples) {
  if (m.one_of({"sample_radius", "sample_mass"}) == "sample_radius") {
    samples.radius = positive(m.get("sample_radius"));
    if (m.has("bulk_density")) fail(m.get("bulk_density"), "belongs with sample_mass, not with sample_radius");
  } else {
    samples.radius = sample_radius_for_mass(positive(m.get("sample_mass")), positive(m.get("bulk_density")),
                                            samples.height / samples.layers);
  }
}

void check_inside_domain(const Map& m, const SampleSpec& smp, const SceneSpec& s) {
  const double reach = smp.ring_radii.back() + smp.radius;
  const bool inside = smp.center_x - reach >= s.domain_min.x && smp.center_x + reach <= s.domain_max.x &&
                      smp.center_y - reach >= s.domain_min.y && smp.center_y + reach <= s.domain_max.y &&
                      smp.bottom >= s.domain_min.z && smp.bottom + smp.height <= s.domain_max.z;
  if (!inside)
    fail(m.self(), "the sample cylinders (out to " + str(reach) + " m from the axis, z from " + str(smp.bottom) +
                       " to " + str(smp.bottom + smp.height) + ") reach outside the domain");
}

// The run opens the mixing log after it has created its output directory, and
// creates no other: a log whose directory is missing is refused here, before
// anything is written.
void check_log_path(const Val& v, const std::string& output) {
  const std::filesystem::path p(output);
  if (!p.has_filename() || (p.is_absolute() && std::filesystem::is_directory(p)))
    fail(v, quoted(output) + " names a directory; give a file name");
  if (p.is_relative() && p.has_parent_path())
    fail(v, "a relative path lies in the run's output directory, which holds files only: give a file name, or an "
            "absolute path to write elsewhere");
  if (p.is_absolute() && !std::filesystem::is_directory(p.parent_path()))
    fail(v, "the directory " + quoted(p.parent_path().string()) + " does not exist");
}

MixingSpec parse_mixing(const Map& m, const SceneSpec& s) {
  MixingSpec spec;
  SampleSpec& smp = spec.samples;
  read_center(m.get("center"), smp);
  smp.bottom = number(m.get("bottom"));
  smp.height = positive(m.get("height"));
  if (m.has("layers")) smp.layers = int(integer(m.get("layers"), 1, 1000));
  const double ring_width = read_rings(m, smp);
  read_sample_size(m, smp);
  const Val size = m.has("sample_radius") ? m.get("sample_radius") : m.get("sample_mass");
  if (ring_width > 0 && !(2 * smp.radius <= ring_width * (1 + 1e-12)))
    fail(size, "gives samples of radius " + str(smp.radius) + " m, too wide for rings " + str(ring_width) +
                   " m wide (the diameter must fit in a ring); use fewer rings or smaller samples");
  const std::string problem = sample_layout_problem(smp);
  if (!problem.empty()) fail(size, problem);
  check_inside_domain(m, smp, s);

  if (m.has("tracer_marker")) spec.tracer_marker = int(integer(m.get("tracer_marker"), 0, 255));
  if (m.has("basis"))
    spec.basis = choice(m.get("basis"), {"number", "mass"}) == "number" ? ConcentrationBasis::number
                                                                        : ConcentrationBasis::mass;
  if (m.has("min_particles")) spec.min_particles = int(integer(m.get("min_particles"), 1, 1000000000));
  if (m.has("min_fill")) {
    const Val f = m.get("min_fill");
    spec.min_fill = number(f);
    if (!(spec.min_fill >= 0 && spec.min_fill <= 1)) fail(f, "must lie in [0, 1], got " + str(spec.min_fill));
  }
  spec.revolution_period = number_or(m, "revolution_period", 0.0, positive);
  if (m.has("every"))
    spec.every = positive(m.get("every"));
  else if (spec.revolution_period > 0)
    spec.every = spec.revolution_period;
  else
    fail(m.self(), "missing required key 'every' (simulated seconds between evaluations; it defaults to "
                   "revolution_period when that is given)");
  spec.start = number_or(m, "start", 0.0, nonnegative);
  if (!(spec.start <= s.duration))
    fail(m.get("start"), "must not exceed the duration " + str(s.duration) + " s, got " + str(spec.start));
  if (m.has("output")) {
    spec.output = text(m.get("output"));
    check_log_path(m.get("output"), spec.output);
  }
  return spec;
}

}  // namespace

void parse_analysis(const Map& top, SceneSpec& s) {
  if (!top.has("analysis")) return;
  const Map analysis(top.get("analysis"), {"mixing"});
  if (analysis.has("mixing")) s.mixing = parse_mixing(Map(analysis.get("mixing"), kMixingKeys), s);
}

}  // namespace gs::scene_yaml
