// `grainstorm run`: one rank, or one rank per GPU (or CPU) under mpirun.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "app/commands.hpp"
#include "backend/memory.hpp"
#include "comm/domain_exchange.hpp"
#include "comm/snapshot_gather.hpp"
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

// Progress to stderr at most every two seconds: step, time, rate, ETA.
class Progress {
 public:
  Progress(long long total, long long particles) : total_(total), particles_(particles) {}
  void update(const Simulation& sim) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_).count() < 2.0 && sim.step_count() < total_) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double done = double(sim.step_count());
    const double rate = elapsed > 0 ? done * double(particles_) / elapsed : 0;
    const double eta = done > 0 ? elapsed * double(total_ - sim.step_count()) / done : 0;
    std::fprintf(stderr, "step %lld/%lld  t = %.6g s  %.3g particle-steps/s  ETA %.0f s\n", sim.step_count(), total_,
                 sim.time(), rate, eta);
  }

 private:
  long long total_, particles_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_ = start_;
};

void print_timings(const Simulation& sim, double wall) {
  const StepTimings& t = sim.timings();
  std::printf("time per phase (s, rank 0): integration %.3f, neighbour build %.3f, contact forces %.3f, "
              "exchange %.3f, total wall %.3f\n",
              t.integrate, t.neighbours, t.forces, t.exchange, wall);
  std::printf("peak %s memory (rank 0): %s\n", backend_name(sim.backend()),
              human_bytes(double(backend_peak_bytes(sim.backend()))).c_str());
}

}  // namespace

int command_run(const std::vector<std::string>& args, Transport& transport) {
  const RunArgs a = parse_run_args(args);
  const SceneSpec scene = load_scene(a.scene);
  const bool root = transport.rank() == 0;
  const long long total = a.steps >= 0 ? a.steps : std::llround(scene.duration / scene.time_step);
  const std::string out = a.out.empty() ? scene.output.directory : a.out;
  if (a.backend == Backend::cuda) select_cuda_device(transport.local_rank());
  RunOptions options;
  options.backend = a.backend;
  std::shared_ptr<DomainExchange> exchange;
  if (transport.size() > 1) exchange = make_domain_exchange(scene, transport);
  Simulation sim(scene, options, exchange);
  const long long particles = exchange ? exchange->total(sim.particle_count()) : sim.particle_count();
  if (root) {
    std::filesystem::create_directories(out);
    std::printf("grainstorm %s: %s, %lld particles, backend %s, %d rank%s, dt = %.4g s (contact time %.4g s), %lld steps\n",
                GS_VERSION, a.scene.c_str(), particles, backend_name(a.backend), transport.size(),
                transport.size() > 1 ? "s" : "", scene.time_step, scene.contact_time, total);
    if (exchange) std::printf("decomposition: %s\n", exchange->describe().c_str());
    std::fflush(stdout);
  }
  auto write_snapshot = [&] {
    const ParticleSnapshot s = gather_snapshot(transport, sim.snapshot());
    if (root) write_particles_csv(out + "/" + snapshot_file_name(sim.step_count()), s);
  };
  const long long every =
      scene.output.interval > 0 ? std::max(1LL, std::llround(scene.output.interval / scene.time_step)) : total;
  const auto start = std::chrono::steady_clock::now();
  Progress progress(total, particles);
  write_snapshot();
  while (sim.step_count() < total) {
    const long long to_output = std::min(every - sim.step_count() % every, total - sim.step_count());
    sim.run(std::min<long long>(to_output, 200));
    if (root) progress.update(sim);
    if (sim.step_count() % every == 0 || sim.step_count() == total) write_snapshot();
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (root) {
    std::printf("done: %lld steps, t = %.6g s, %.3g particle-steps/s, output in %s\n", total, sim.time(),
                wall > 0 ? double(total) * double(particles) / wall : 0.0, out.c_str());
    if (exchange) std::printf("decomposition at the end: %s\n", exchange->describe().c_str());
    print_timings(sim, wall);
  }
  return 0;
}

}  // namespace gs
