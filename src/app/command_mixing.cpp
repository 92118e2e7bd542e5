// `grainstorm mixing`: the scene's mixing analysis over snapshots already
// written, e.g. again with other samples (--layers) after a run.
#include <cstdio>
#include <stdexcept>

#include "analysis/mixing.hpp"
#include "analysis/mixing_log.hpp"
#include "app/commands.hpp"
#include "contact/contact_time.hpp"
#include "io/h5_snapshot.hpp"
#include "scene/scene_loader.hpp"

namespace gs {
namespace {

// Masses as the run computed them (Simulation::upload), for snapshots
// written without the mass field.
void fill_masses(ParticleSnapshot& s, const SceneSpec& scene, const std::string& path) {
  if (s.mass.size() == s.size() && !s.mass.empty()) return;
  if (s.radius.size() != s.position.size())
    throw std::invalid_argument(path + ": the snapshot holds neither mass nor radius, which the analysis needs");
  s.mass.resize(s.radius.size());
  for (std::size_t i = 0; i < s.radius.size(); ++i) {
    const std::size_t material = s.material.empty() ? 0 : s.material[i];
    if (material >= scene.materials.size())
      throw std::invalid_argument(path + ": particle material " + std::to_string(material) + " is not in the scene");
    s.mass[i] = float(sphere_mass(double(s.radius[i]), scene.materials[material].density));
  }
}

}  // namespace

int command_mixing(const std::vector<std::string>& args) {
  const char* usage = "usage: grainstorm mixing SCENE SNAPSHOT.h5... --out FILE.csv [--layers L]";
  std::vector<std::string> snapshots;
  std::string out;
  int layers = 0;
  for (std::size_t k = 2; k < args.size(); ++k) {
    if (args[k] == "--out" || args[k] == "--layers") {
      if (k + 1 >= args.size()) throw std::invalid_argument(args[k] + " needs a value; " + usage);
      if (args[k] == "--out") out = args[++k];
      else {
        layers = int(whole_number(args[++k], 1, 1000, "--layers must be an integer in [1, 1000]"));
      }
    } else if (args[k].rfind("--", 0) == 0) {
      throw std::invalid_argument("unknown option " + args[k] + "; " + usage);
    } else {
      snapshots.push_back(args[k]);
    }
  }
  if (args.size() < 2 || snapshots.empty() || out.empty()) throw std::invalid_argument(usage);
  const SceneSpec scene = load_scene(args[1]);
  if (!scene.mixing) throw std::invalid_argument(args[1] + ": the scene has no analysis.mixing section");
  MixingSpec spec = *scene.mixing;
  // The scene's cylinders, cut into `layers` stacked samples (each holds a
  // layer's share of a cylinder's mass).
  if (layers > 0) spec.samples.layers = layers;
  // Everything is read and evaluated before the log is written: a bad file leaves no partial log.
  std::vector<MixingResult> results;
  for (const std::string& path : snapshots) {
    ParticleSnapshot s = read_snapshot(path);
    if (s.position.empty() || s.marker.size() != s.position.size())
      throw std::invalid_argument(path + ": the snapshot needs the position and marker fields");
    fill_masses(s, scene, path);
    results.push_back(evaluate_mixing(spec, s));
  }
  MixingLog log(out, spec.revolution_period, spec.start);
  for (const MixingResult& r : results) log.append(r);
  std::printf("%zu snapshots analysed into %s (%d samples of %d layer%s)\n", results.size(), out.c_str(),
              results.empty() ? 0 : results.front().samples_total, spec.samples.layers,
              spec.samples.layers > 1 ? "s" : "");
  return 0;
}

}  // namespace gs
