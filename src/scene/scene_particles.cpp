// The `particles:` section of a scene and the checks of the initial packing.
#include <algorithm>
#include <climits>
#include <cmath>
#include <iterator>

#include "scene/fill_blocks.hpp"
#include "scene/generators.hpp"
#include "scene/packing_check.hpp"
#include "scene/particle_sources.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_sections.hpp"

namespace gs::scene_yaml {

ParticleTemplate parse_template(const SceneSpec& s, const Map& m) {
  ParticleTemplate t;
  t.material = material_index(s, m.get("material"));
  t.velocity = vec3_or(m, "velocity", Vec3d());
  t.angular_velocity = vec3_or(m, "angular_velocity", Vec3d());
  if (m.has("marker")) t.marker = std::uint8_t(integer(m.get("marker"), 0, 255));
  return t;
}

// `frozen: true` on a particle set (not an inlet): its particles never move
// but push on those that touch them (a rough base). A frozen particle starts
// and stays at rest, so a velocity beside it is a slip.
static ParticleTemplate parse_set_template(SceneSpec& s, const Map& m) {
  ParticleTemplate t = parse_template(s, m);
  if (!m.has("frozen") || !boolean(m.get("frozen"))) return t;
  for (const char* key : {"velocity", "angular_velocity"})
    if (m.has(key) && norm2(vec3(m.get(key))) > 0)
      fail(m.get(key), std::string("a frozen particle never moves: its ") + key + " must be zero");
  t.frozen = true;
  s.frozen_particles = true;
  return t;
}

FillRegion parse_region(const Val& v) {
  const Map m(v, {"box", "cylinder"});
  FillRegion r;
  if (m.one_of({"box", "cylinder"}) == "box") {
    r.kind = FillRegion::Kind::box;
    box_corners(Map(m.get("box"), {"min", "max"}), r.min, r.max);
    return r;
  }
  const Map c(m.get("cylinder"), {"base", "axis", "radius", "length"});
  r.kind = FillRegion::Kind::cylinder;
  r.base = vec3(c.get("base"));
  r.axis = unit_vector(c.get("axis"));
  r.radius = positive(c.get("radius"));
  r.length = positive(c.get("length"));
  return r;
}

static std::vector<SizeClass> parse_distribution(const Val& v) {
  std::vector<SizeClass> classes;
  double total = 0;
  for_each_item(v, [&](const Val& item, std::size_t) {
    const Map m(item, {"diameter", "fraction"});
    classes.push_back({positive(m.get("diameter")), positive(m.get("fraction"))});
    total += classes.back().fraction;
  });
  if (classes.empty()) fail(v, "the distribution needs at least one diameter");
  // Fractions written as rounded decimals (0.33, 0.33, 0.34) are fine; a sum
  // that is plainly off is a slip worth reporting.
  if (std::abs(total - 1) > 1e-3) fail(v, "the fractions must add up to 1, they add up to " + str(total));
  for (auto& c : classes) c.fraction /= total;
  return classes;
}

SizeSpec parse_sizes(const Map& m) {
  SizeSpec size;
  if (m.one_of({"radius", "diameter_distribution"}) == "diameter_distribution") {
    size.kind = SizeSpec::Kind::classes;
    size.classes = parse_distribution(m.get("diameter_distribution"));
    if (m.has("fractions_by") && choice(m.get("fractions_by"), {"count", "mass"}) == "mass")
      size.classes = count_fractions_from_mass(size.classes);
    return size;
  }
  if (m.has("fractions_by")) fail(m.get("fractions_by"), "applies to a diameter_distribution only");
  const Val r = m.get("radius");
  if (!r.node.IsMap()) {
    size.kind = SizeSpec::Kind::fixed;
    size.radius_min = size.radius_max = positive(r);
    return size;
  }
  const Map range(r, {"min", "max"});
  size.kind = SizeSpec::Kind::uniform;
  size.radius_min = positive(range.get("min"));
  size.radius_max = positive(range.get("max"));
  if (size.radius_max < size.radius_min)
    fail(r, "max " + str(size.radius_max) + " is below min " + str(size.radius_min));
  return size;
}

namespace {

// Where the particles from id `first` on were defined.
void add_origin(SceneSpec& s, std::size_t first, const Val& where) {
  s.set_origins.push_back({first, where.line, where.path});
}

// Runs a generator; its complaints become errors at the set's line.
template <class F>
void generate(const Val& where, F&& f) {
  try {
    f();
  } catch (const GenerateError& e) {
    fail(where, e.what());
  }
}

void add_lattice(SceneSpec& s, const Val& v) {
  const Map m(v, {"material", "radius", "min", "max", "spacing", "velocity", "angular_velocity", "marker", "frozen"});
  LatticeSpec spec;
  spec.tmpl = parse_set_template(s, m);
  spec.radius = positive(m.get("radius"));
  spec.min = vec3(m.get("min"));
  spec.max = vec3(m.get("max"));
  // 5 % of the diameter between neighbours: close, but not touching at t = 0.
  spec.spacing = number_or(m, "spacing", 2.1 * spec.radius, positive);
  if (spec.spacing < 2 * spec.radius)
    fail(m.opt("spacing"), "spacing " + str(spec.spacing) + " is below the particle diameter " +
                               str(2 * spec.radius) + ": neighbours would overlap");
  std::size_t sites = 0;
  generate(v, [&] { sites = lattice_count(spec); });
  if (sites == 0) fail(v, "no lattice site lies in [min, max]: min exceeds max on some axis");
  // Kept as its description: ranks generate the sites they need (particle_sources.hpp).
  const std::size_t first = particle_count(s);
  generate(v, [&] { check_id_room(first, sites); });
  s.lattices.push_back({spec, ParticleId(first), sites});
}

void add_random_fill(SceneSpec& s, const Val& v) {
  const Map m(v, {"material", "region", "count", "radius", "diameter_distribution", "fractions_by", "seed",
                  "velocity", "angular_velocity", "marker", "frozen"});
  RandomFillSpec spec;
  spec.tmpl = parse_set_template(s, m);
  spec.region = parse_region(m.get("region"));
  spec.count = std::size_t(integer(m.get("count"), 1, kMaxParticleId));
  spec.size = parse_sizes(m);
  if (m.has("seed")) spec.seed = std::uint64_t(integer(m.get("seed"), 0, LLONG_MAX));
  // Kept as its description: blocks are placed where needed (scene/fill_blocks.hpp).
  const std::size_t first = particle_count(s);
  generate(v, [&] { s.fills.push_back(make_fill_source(spec, first)); });
}

void add_list(SceneSpec& s, const Val& v) {
  for_each_item(v, [&](const Val& item, std::size_t) {
    const Map m(item, {"position", "radius", "material", "velocity", "angular_velocity", "marker", "frozen"});
    const ParticleTemplate t = parse_set_template(s, m);
    const std::size_t id = particle_count(s);
    if (id > kMaxParticleId) fail(item, "too many particles for 32-bit ids");
    ParticleInit p;
    p.id = ParticleId(id);
    p.material = t.material;
    p.radius = positive(m.get("radius"));
    p.position = vec3(m.get("position"));
    p.velocity = t.velocity;
    p.angular_velocity = t.angular_velocity;
    p.marker = t.marker;
    p.frozen = std::uint8_t(t.frozen);
    add_origin(s, id, item);
    s.particles.push_back(p);
  });
}

}  // namespace

void parse_particles(const Map& top, SceneSpec& s, PackingChecks checks) {
  const Val list = top.has("inlets") ? top.opt("particles") : top.get("particles");
  if (!list.present()) return;
  for_each_item(list, [&](const Val& item, std::size_t) {
    const Map m(item, {"lattice", "random_fill", "list"});
    const std::string kind = m.one_of({"lattice", "random_fill", "list"});
    const Val set = m.get(kind);
    add_origin(s, particle_count(s), set);
    if (kind == "lattice") add_lattice(s, set);
    if (kind == "random_fill") add_random_fill(s, set);
    if (kind == "list") add_list(s, set);
  });
  if (particle_count(s) == 0) {
    if (top.has("inlets")) return;  // a scene with inlets may start empty (a silo being filled)
    fail(list, "the scene has no particles");
  }
  // A run's ranks check the particles each makes anyway (src/run/packing_on_ranks.hpp).
  if (checks == PackingChecks::here) check_packing(s);
}

}  // namespace gs::scene_yaml
