#include "scene/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <sys/stat.h>

#include "scene/scene_time_step.hpp"
#include "contact/contact_models.hpp"
#include "io/snapshot_fields.hpp"
#include "neighbor/cell_grid.hpp"
#include "scene/generators.hpp"
#include "scene/particle_sources.hpp"
#include "scene/position_resolution.hpp"
#include "scene/scene_sections.hpp"

namespace gs {

using namespace scene_yaml;

namespace {

const std::vector<std::string> kTopKeys = {"domain",    "gravity", "contact_model", "precision",     "effects",
                                           "materials", "pairs",   "particles",     "walls",         "time_step",
                                           "duration",  "output",  "contact_slots", "decomposition",
                                           "analysis",  "marking", "outlets",       "inlets",
                                           "measurements", "surface_slots", "verlet_skin"};

// In largest diameters: 0 rebuilds the list at every step; beyond one
// diameter the list (and the halo) would hold more than eight times the
// neighbours a contact needs, which no flow repays.
double verlet_skin(const Val& v) {
  const double x = nonnegative(v);
  if (x > 1) fail(v, "must be at most 1 (largest diameters), got " + str(x));
  return x;
}

void parse_decomposition(const Map& m, SceneSpec& s) {
  DecompositionSpec& d = s.decomposition;
  if (m.has("method"))
    d.method = choice(m.get("method"), {"slabs", "metis"}) == "slabs" ? DecompositionMethod::slabs
                                                                     : DecompositionMethod::metis;
  if (m.has("axis")) {
    const std::string a = choice(m.get("axis"), {"auto", "x", "y", "z"});
    d.axis = a == "auto" ? -1 : a[0] - 'x';
  }
  if (m.has("rebalance_threshold")) {
    const Val t = m.get("rebalance_threshold");
    d.rebalance_threshold = number(t);
    if (!(d.rebalance_threshold >= 1)) fail(t, "must be >= 1 (max / mean particles per rank), got " + str(d.rebalance_threshold));
  }
}

void parse_globals(const Map& top, SceneSpec& s) {
  const Map domain(top.get("domain"), {"min", "max", "open", "periodic"});
  box_corners(domain, s.domain_min, s.domain_max);
  if (domain.has("periodic")) s.periodic_axes = parse_periodic_axes(domain.get("periodic"));
  parse_open_faces(domain, s);
  check_open_periodic_faces(domain, s);
  s.gravity = vec3_or(top, "gravity", Vec3d());
  if (top.has("contact_model"))
    s.model = contact_model_named(choice(top.get("contact_model"), contact_model_names()));
  if (top.has("precision")) {
    const std::string p = choice(top.get("precision"), {"fp32", "fp64", "fp32_full"});
    s.precision = p == "fp64" ? Precision::fp64 : p == "fp32" ? Precision::fp32 : Precision::fp32_full;
  }
  if (top.has("effects")) {
    const Map e(top.get("effects"), {"friction", "rolling_resistance", "cohesion"});
    const std::pair<const char*, Effect> bits[] = {
        {"friction", kFriction}, {"rolling_resistance", kRollingResistance}, {"cohesion", kCohesion}};
    for (const auto& [key, bit] : bits)
      if (e.has(key) && boolean(e.get(key))) s.effects |= bit;
  }
  s.duration = positive(top.get("duration"));
  if (top.has("output")) {
    const Map o(top.get("output"),
                {"interval", "directory", "format", "fields", "checkpoint_interval", "checkpoint_minutes"});
    s.output.interval = number_or(o, "interval", 0.0, nonnegative);
    if (o.has("directory")) s.output.directory = text(o.get("directory"));
    if (o.has("format")) s.output.format = choice(o.get("format"), {"hdf5", "csv"});
    if (o.has("fields")) {
      const Val list = o.get("fields");
      for_each_item(list, [&](const Val& item, std::size_t) { s.output.fields.push_back(text(item)); });
      SnapshotFields fields;
      try {
        fields = parse_snapshot_fields(s.output.fields);
      } catch (const std::invalid_argument& e) {
        fail(list, cut(e.what(), 4 * kEchoLength));
      }
      // Contacts are counted in the contact history, which only these effects and models keep.
      if (fields.has(SnapshotField::contact_count) && !keeps_history(s.model, s.effects))
        fail(list, "contact_count needs a contact history (friction, rolling resistance or the hysteretic_linear "
                   "contact model); set effects.friction or effects.rolling_resistance, use contact_model: "
                   "hysteretic_linear, or leave the field out");
      if (fields.has(SnapshotField::image) && s.periodic_axes == 0)
        fail(list, "image (image counts) is kept only by periodic runs; set domain.periodic, or leave the field out");
    }
    s.output.checkpoint_interval = number_or(o, "checkpoint_interval", 0.0, nonnegative);
    s.output.checkpoint_minutes = number_or(o, "checkpoint_minutes", 0.0, nonnegative);
  }
  if (top.has("contact_slots")) s.contact_slots = int(integer(top.get("contact_slots"), 1, kMaxContactSlots));
  if (top.has("surface_slots")) s.surface_slots = int(integer(top.get("surface_slots"), 1, kMaxContactSlots));
  if (top.has("verlet_skin")) s.verlet_skin = verlet_skin(top.get("verlet_skin"));
  if (top.has("decomposition")) parse_decomposition(Map(top.get("decomposition"), {"method", "axis", "rebalance_threshold"}), s);
}

void parse_materials(const Map& top, SceneSpec& s) {
  const Val list = top.get("materials");
  const bool hertz = with_contact_model(s.model, [](auto m) { return decltype(m)::kNeedsElasticConstants; });
  for_each_item(list, [&](const Val& item, std::size_t) {
    const Map m(item, {"name", "density", "youngs_modulus", "poisson_ratio"});
    MaterialSpec mat;
    mat.name = text(m.get("name"));
    for (const auto& other : s.materials)
      if (other.name == mat.name) fail(m.get("name"), "material " + quoted(mat.name) + " is defined twice");
    mat.density = positive(m.get("density"));
    // Elastic constants matter to Hertz-Mindlin only; elsewhere they are optional but still checked.
    mat.youngs_modulus = hertz ? positive(m.get("youngs_modulus")) : number_or(m, "youngs_modulus", 0.0, positive);
    const Val nu = hertz ? m.get("poisson_ratio") : m.opt("poisson_ratio");
    if (nu.present()) {
      mat.poisson_ratio = number(nu);
      if (mat.poisson_ratio < 0 || mat.poisson_ratio >= 0.5)
        fail(nu, "must lie in [0, 0.5), got " + str(mat.poisson_ratio));
    }
    s.materials.push_back(mat);
  });
  if (s.materials.empty()) fail(list, "at least one material is needed");
}

PairSpec parse_pair(const SceneSpec& s, const Map& m) {
  const Val names = m.get("materials");
  if (!names.node.IsSequence() || names.node.size() != 2)
    fail(names, "expected a list of two material names, got " + describe(names.node));
  int idx[2];
  for_each_item(names, [&](const Val& item, std::size_t i) { idx[i] = material_index(s, item); });
  PairSpec p;
  p.material_a = std::min(idx[0], idx[1]);
  p.material_b = std::max(idx[0], idx[1]);
  for (const auto& q : s.pairs)
    if (q.material_a == p.material_a && q.material_b == p.material_b)
      fail(names, "the pair [" + s.materials[p.material_a].name + ", " + s.materials[p.material_b].name +
                      "] is given twice");

  const bool linear = with_contact_model(s.model, [](auto m) { return decltype(m)::kNeedsStiffness; });
  p.stiffness_normal = linear ? positive(m.get("stiffness_normal")) : number_or(m, "stiffness_normal", 0.0, positive);
  // k_t = 2/7 k_n gives a sphere the same tangential as normal oscillation period.
  p.stiffness_tangential = number_or(m, "stiffness_tangential", 2.0 / 7.0 * p.stiffness_normal, positive);
  // Hertz-Mindlin has no linear k_t to borrow the rolling spring from.
  const bool rolling_required = !linear && (s.effects & kRollingResistance);
  p.stiffness_rolling = rolling_required ? positive(m.get("stiffness_rolling"))
                                         : number_or(m, "stiffness_rolling", p.stiffness_tangential, positive);
  const Val e = m.get("restitution");
  p.restitution = number(e);
  if (!(p.restitution > 0 && p.restitution <= 1)) fail(e, "must lie in (0, 1], got " + str(p.restitution));
  p.friction = number_or(m, "friction", 0.0, nonnegative);
  p.rolling_friction = number_or(m, "rolling_friction", 0.0, nonnegative);
  p.cohesion_energy_density = number_or(m, "cohesion_energy_density", 0.0, nonnegative);
  return p;
}

// A pair's parameters of an effect that is off are read and checked, then
// ignored by the run: say so. A friction, rolling friction or cohesion of 0
// agrees with the effect being off; a stiffness is always a choice.
void warn_unused_parameters(const Map& m, SceneSpec& s) {
  struct Use {
    const char* key;
    Effect effect;
    const char* effect_key;
    bool zero_agrees;
  };
  const Use uses[] = {{"friction", kFriction, "friction", true},
                      {"stiffness_tangential", kFriction, "friction", false},
                      {"rolling_friction", kRollingResistance, "rolling_resistance", true},
                      {"stiffness_rolling", kRollingResistance, "rolling_resistance", false},
                      {"cohesion_energy_density", kCohesion, "cohesion", true}};
  for (const Use& u : uses) {
    if (!m.has(u.key) || (s.effects & u.effect)) continue;
    const Val v = m.get(u.key);
    if (u.zero_agrees && number(v) == 0) continue;
    s.warnings.push_back(located(v, std::string("ignored: the effect ") + u.effect_key + " is off (set effects: {" +
                                        u.effect_key + ": true} to use it)"));
  }
}

bool has_pair(const SceneSpec& s, int a, int b) {
  for (const auto& p : s.pairs)
    if (p.material_a == std::min(a, b) && p.material_b == std::max(a, b)) return true;
  return false;
}

// Every pair of materials that can touch needs contact parameters: particle
// materials among themselves and with every wall material.
void require_pairs(const SceneSpec& s, const Val& where) {
  const std::size_t n = s.materials.size();
  std::vector<char> on_particle(n, 0), on_wall(n, 0);
  for_each_radius(s, [&](int material, double) { on_particle[std::size_t(material)] = 1; });
  for (const auto& w : s.walls) on_wall[w.material] = 1;
  for (const auto m : s.meshes.material) on_wall[m] = 1;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a; b < n; ++b) {
      const bool touch = (on_particle[a] && (on_particle[b] || on_wall[b])) || (on_wall[a] && on_particle[b]);
      if (touch && !has_pair(s, int(a), int(b)))
        fail(where, "no entry for the material pair [" + s.materials[a].name + ", " + s.materials[b].name +
                        "]; every pair of materials that can touch needs one");
    }
}

void parse_pairs(const Map& top, SceneSpec& s) {
  const Val list = top.opt("pairs");
  if (list.present())
    for_each_item(list, [&](const Val& item, std::size_t) {
      const Map m(item, {"materials", "stiffness_normal", "stiffness_tangential", "stiffness_rolling", "restitution",
                         "friction", "rolling_friction", "cohesion_energy_density"});
      s.pairs.push_back(parse_pair(s, m));
      warn_unused_parameters(m, s);
    });
  require_pairs(s, list);
}

double largest_diameter(const SceneSpec& s) { return 2 * largest_radius(s); }

// The run's contact search lays cells of at least the largest diameter over
// the domain (walls/mesh.hpp bins meshes in the same cells); refused here
// what its grid would refuse, so that check refuses it too.
void check_search_grid(const Map& top, const SceneSpec& s) {
  const double cell = largest_diameter(s);
  const double cells = grid_cells(s.domain_min, s.domain_max, cell);
  if (!(cells <= kMaxGridCells))
    fail(top.get("domain"), "the contact search needs cells of at least " + str(cell) +
                                " m (the largest particle diameter): over the domain's extent " +
                                str(s.domain_max - s.domain_min) + " m that is " + str(cells) + " cells, more than " +
                                str(kMaxGridCells) + "; shrink the domain to where the particles can go");
  // Meshes are binned in the run's cells: a diameter and the Verlet skin.
  check_mesh_binning(top, s, cell * (1 + s.verlet_skin), cell * s.verlet_skin);
}

void resolve_time_step(const Map& top, SceneSpec& s) {
  const Val v = top.get("time_step");
  const Map m(v, {"absolute", "fraction_of_contact_time"});
  const std::string kind = m.one_of({"absolute", "fraction_of_contact_time"});
  s.contact_time = critical_contact_time(s);
  s.time_step = positive(m.get(kind));
  if (kind == "fraction_of_contact_time") s.time_step *= s.contact_time;
  if (const std::string problem = time_step_problem(s); !problem.empty()) fail(v, problem);
  // A run's time is its step count times the time step: whole steps, exact
  // in fp64 up to 2^53.
  const double steps = s.duration / s.time_step;
  if (!(steps <= 0x1p53))
    fail(v, "time step " + str(s.time_step) + " s makes " + str(steps) + " steps of the duration " +
                str(s.duration) + " s, more than 2^53");
  if (std::llround(steps) < 1)
    fail(v, "time step " + str(s.time_step) + " s is longer than twice the duration " + str(s.duration) +
                " s: the run would make no step");
}

}  // namespace

SceneSpec parse_scene(const std::string& yaml_text, const std::string& source, PackingChecks checks) {
  const YAML::Node root = load_document(yaml_text, source);
  SceneSpec s;
  s.path = source;
  const Map top(Val{root, "", 1, &source}, kTopKeys);
  parse_globals(top, s);
  parse_materials(top, s);
  parse_walls(top, s);
  parse_particles(top, s, checks);
  parse_inlets(top, s);
  parse_pairs(top, s);
  check_periodic_box(top, s);
  check_search_grid(top, s);
  resolve_time_step(top, s);
  check_inlet_rates(top, s);
  if (const std::string problem = fp32_state_problem(s); !problem.empty()) fail(top.get("precision"), problem);
  parse_analysis(top, s);
  parse_marking(top, s);
  parse_outlets(top, s);
  parse_measurements(top, s);
  return s;
}

SceneSpec load_scene(const std::string& path, PackingChecks checks) {
  // A directory opens, and then reads as an empty scene.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw SceneError(path + ":1: scene: a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ":1: scene: cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();  // an empty file leaves `text` empty, which parse_scene reports
  return parse_scene(text.str(), path, checks);
}

}  // namespace gs
