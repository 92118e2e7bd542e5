#include "app/commands.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "engine/memory_estimate.hpp"
#include "engine/simulation.hpp"
#include "io/particle_csv.hpp"
#include "scene/scene_loader.hpp"

namespace gs {
namespace {

struct RunArgs {
  std::string scene;
  Backend backend = default_backend();
  long long steps = -1;
  std::string out;
};

RunArgs parse_run_args(const std::vector<std::string>& args) {
  RunArgs r;
  for (std::size_t k = 1; k < args.size(); ++k) {
    const std::string& a = args[k];
    auto value = [&]() -> const std::string& {
      if (k + 1 >= args.size()) throw std::invalid_argument("option " + a + " needs a value");
      return args[++k];
    };
    if (a == "--backend") r.backend = parse_backend(value());
    else if (a == "--steps") r.steps = std::stoll(value());
    else if (a == "--out") r.out = value();
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else if (r.scene.empty()) r.scene = a;
    else throw std::invalid_argument("more than one scene given: " + a);
  }
  if (r.scene.empty()) throw std::invalid_argument("no scene file given");
  if (r.steps < -1) throw std::invalid_argument("--steps must be >= 0");
  return r;
}

std::string human_bytes(double b) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  while (b >= 1024 && u < 4) { b /= 1024; ++u; }
  char s[32];
  std::snprintf(s, sizeof(s), "%.1f %s", b, units[u]);
  return s;
}

// Progress to stderr at most every two seconds: step, time, rate, ETA.
class Progress {
 public:
  Progress(long long total, Index particles) : total_(total), particles_(particles) {}
  void update(const Simulation& sim) {
    const auto now = std::chrono::steady_clock::now();
    const double since_print = std::chrono::duration<double>(now - last_).count();
    if (since_print < 2.0 && sim.step_count() < total_) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double done = double(sim.step_count() - first_step_);
    const double rate = elapsed > 0 ? done * particles_ / elapsed : 0;
    const double eta = done > 0 ? elapsed * double(total_ - sim.step_count()) / done : 0;
    std::fprintf(stderr, "step %lld/%lld  t = %.6g s  %.3g particle-steps/s  ETA %.0f s\n", sim.step_count(), total_,
                 sim.time(), rate, eta);
  }

 private:
  long long total_;
  Index particles_;
  long long first_step_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_ = start_;
};

void print_timings(const Simulation& sim, double wall) {
  const StepTimings& t = sim.timings();
  std::printf("time per phase (s): integration %.3f, neighbour build %.3f, contact forces %.3f, total wall %.3f\n",
              t.integrate, t.neighbours, t.forces, wall);
  std::printf("peak %s memory: %s\n", backend_name(sim.backend()), human_bytes(double(backend_peak_bytes(sim.backend()))).c_str());
}

}  // namespace

int command_run(const std::vector<std::string>& args) {
  const RunArgs a = parse_run_args(args);
  const SceneSpec scene = load_scene(a.scene);
  const long long total = a.steps >= 0 ? a.steps : std::llround(scene.duration / scene.time_step);
  const std::string out = a.out.empty() ? scene.output.directory : a.out;
  RunOptions options;
  options.backend = a.backend;
  Simulation sim(scene, options);
  std::filesystem::create_directories(out);
  std::printf("grainstorm %s: %s, %d particles, backend %s, dt = %.4g s (contact time %.4g s), %lld steps\n",
              GS_VERSION, a.scene.c_str(), int(sim.particle_count()), backend_name(a.backend), scene.time_step,
              scene.contact_time, total);
  const long long every =
      scene.output.interval > 0 ? std::max(1LL, std::llround(scene.output.interval / scene.time_step)) : total;
  const auto start = std::chrono::steady_clock::now();
  Progress progress(total, sim.particle_count());
  write_particles_csv(out + "/" + snapshot_file_name(0), sim.snapshot());
  while (sim.step_count() < total) {
    const long long chunk = std::min(every - sim.step_count() % every, total - sim.step_count());
    const long long slice = std::min<long long>(chunk, 200);
    sim.run(slice);
    progress.update(sim);
    if (sim.step_count() % every == 0 || sim.step_count() == total)
      write_particles_csv(out + "/" + snapshot_file_name(sim.step_count()), sim.snapshot());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("done: %lld steps, t = %.6g s, %.3g particle-steps/s, output in %s\n", total, sim.time(),
              wall > 0 ? double(total) * sim.particle_count() / wall : 0.0, out.c_str());
  print_timings(sim, wall);
  return 0;
}

int command_check(const std::vector<std::string>& args) {
  if (args.size() != 2) throw std::invalid_argument("usage: grainstorm check SCENE");
  const SceneSpec scene = load_scene(args[1]);
  const MemoryEstimate m = estimate_memory(scene);
  std::printf("scene %s is valid\n", args[1].c_str());
  std::printf("particles:      %zu\n", scene.particles.size());
  std::printf("walls:          %zu\n", scene.walls.size());
  std::printf("contact time:   %.6g s\n", scene.contact_time);
  std::printf("time step:      %.6g s (%.4g of the contact time)\n", scene.time_step,
              scene.time_step / scene.contact_time);
  std::printf("steps:          %lld\n", std::llround(scene.duration / scene.time_step));
  std::printf("memory:         %s (%.0f bytes per particle, %s for %lld cells)\n",
              human_bytes(m.total_bytes).c_str(), m.bytes_per_particle, human_bytes(m.cell_bytes).c_str(),
              m.cells);
  return 0;
}

}  // namespace gs
