#include "run/driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "run/edited_restart.hpp"
#include "run/insertion_log.hpp"
#include "run/packing_on_ranks.hpp"
#include "run/output_directory.hpp"
#include "run/run_measurements.hpp"
#include "run/run_output.hpp"
#include "engine/schedule.hpp"
#include "backend/memory.hpp"
#include "comm/domain_exchange.hpp"
#include "comm/rank_agreement.hpp"
#include "comm/scene_split.hpp"
#include "comm/device_link.hpp"
#include "core/wall_clock.hpp"
#include "engine/simulation.hpp"
#include "io/fnv1a.hpp"
#include "io/restart.hpp"
#include "scene/kept_fill_blocks.hpp"
#include "scene/scene_loader.hpp"

namespace gs {

std::string human_bytes(double b) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  while (b >= 1024 && u < 4) { b /= 1024; ++u; }
  char s[32];
  std::snprintf(s, sizeof(s), "%.1f %s", b, units[u]);
  return s;
}

void print_warnings(const SceneSpec& scene) {
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

void check_request(const RunRequest& r) {
  if (r.scene.empty()) throw std::invalid_argument("no scene file given");
  if (r.steps < -1) throw std::invalid_argument("--steps must be >= 0");
  if (r.exchange != "auto" && r.exchange != "device" && r.exchange != "host")
    throw std::invalid_argument("--exchange must be auto, device or host, got " + r.exchange);
  if (r.exchange == "device" && r.backend != Backend::cuda)
    throw std::invalid_argument("--exchange device needs --backend cuda");
  if (r.overwrite && !r.restart.empty())
    throw std::invalid_argument("--overwrite and --restart exclude each other: a restart continues the run in its "
                                "output directory");
  if (r.edited_scene && r.restart.empty())
    throw std::invalid_argument("--edited-scene needs --restart: it continues a checkpoint under an edited scene");
}

namespace {
OutputDirectoryUse directory_use(const RunRequest& a) {
  if (!a.restart.empty()) return OutputDirectoryUse::restart;
  return a.overwrite ? OutputDirectoryUse::overwrite : OutputDirectoryUse::fresh;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  if (!in.good() && !in.eof()) throw std::runtime_error("cannot read " + path);
  return ss.str();
}

// Ranks started with different scenes or options (an MPMD launch, a scene
// file edited while the job started) would split different particles, or
// enter different collectives: every rank must run what rank 0 runs.
void expect_same_run_everywhere(Transport& transport, const RunRequest& a, std::uint64_t hash,
                                const SceneSpec& scene) {
  // The meshes as read, walls' and flow surfaces' (the scene text names
  // their files, which each rank reads: a node-local copy may differ).
  Fnv1a64 read;
  read.add_array(scene.meshes.reference);
  read.add_array(scene.meshes.corners);
  for (const FlowSpec& f : scene.measurements.flows) {
    read.add_array(f.surface.vertices);
    read.add_array(f.surface.triangles);
  }
  const std::string mine = std::to_string(hash) + "\n" + hex64(read.value()) + "\n" + std::to_string(a.steps) +
                           "\n" + backend_name(a.backend) + "\n" + a.exchange + "\n" + a.out + "\n" +
                           (a.overwrite ? "overwrite" : "") + "\n" + (a.restart.empty() ? "new" : "restart") +
                           (a.edited_scene ? " edited" : "");
  const Bytes first = transport.broadcast(Bytes(mine.begin(), mine.end()), 0);
  std::string error;
  if (std::string(first.begin(), first.end()) != mine)
    error = "runs " + a.scene +
            " (scene hash, meshes read, --steps, --backend, --exchange, --out, --overwrite, --restart or "
            "--edited-scene) differently from rank 0: every rank must run the same scene with the same options";
  throw_if_any_failed(transport, error);
}

// An edited restart's report over all ranks: returns the wall contacts
// released on every rank, and sets the history fields any rank started.
std::size_t summed_over_ranks(Transport& transport, EditedRestart& edits) {
  const unsigned bits[] = {kTangentialSprings, kRollingSprings, kPeakOverlap};
  std::vector<std::int64_t> seen = {std::int64_t(edits.dropped_wall_contacts)};
  for (unsigned bit : bits) seen.push_back((edits.started_fields & bit) ? 1 : 0);
  transport.sum(seen);
  for (std::size_t k = 0; k < std::size(bits); ++k)
    if (seen[k + 1] > 0) edits.started_fields |= bits[k];
  return std::size_t(seen[0]);
}

long long steps_per(double interval, double dt) {
  return interval > 0 ? std::max(1LL, std::llround(interval / dt)) : 0;
}

// Progress to stderr at most every two seconds: step, time, rate, ETA. Only
// rank 0 prints it (every rank would repeat the same line). The rate counts
// the particles of each stretch of steps, as they change when particles are
// removed.
class Progress {
 public:
  Progress(long long first, long long total, long long particles, bool prints)
      : first_(first), last_step_(first), total_(total), particles_(particles), prints_(prints) {}
  // After the steps up to sim's, which ran with the count of the previous
  // call; `particles` is the count now.
  void update(const Simulation& sim, long long particles) {
    particle_steps_ += double(sim.step_count() - last_step_) * double(particles_);
    last_step_ = sim.step_count();
    const bool changed = particles != particles_;
    particles_ = particles;
    if (!prints_) return;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_).count() < 2.0 && sim.step_count() < total_) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double done = double(sim.step_count() - first_);
    const double eta = done > 0 ? elapsed * double(total_ - sim.step_count()) / done : 0;
    std::fprintf(stderr, "step %lld/%lld  t = %.6g s  %.3g particle-steps/s  ETA %.0f s", sim.step_count(), total_,
                 sim.time(), rate(), eta);
    if (changed || varies_) std::fprintf(stderr, "  %lld particles", particles_);
    varies_ = varies_ || changed;
    std::fprintf(stderr, "\n");
  }
  // Particle-steps per second of wall time so far.
  double rate() const {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    return elapsed > 0 ? particle_steps_ / elapsed : 0;
  }

 private:
  long long first_, last_step_, total_, particles_;
  bool prints_;
  bool varies_ = false;  // the count has changed: every line shows it
  double particle_steps_ = 0;
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

// GPU ranks move particles over NCCL when asked to, or by default when it is
// built in and every rank has a GPU of its own (NCCL refuses two ranks on one
// device). Collective.
std::shared_ptr<DomainExchange> with_link(std::shared_ptr<DomainExchange> exchange, const RunRequest& a,
                                          Transport& transport, bool own_gpu) {
  bool device = a.exchange == "device";
  if (a.exchange == "auto" && a.backend == Backend::cuda && nccl_available())
    device = transport.min(own_gpu ? 1 : 0) == 1;
  if (exchange && device) exchange->use_device_link(make_nccl_link(transport));
  return exchange;
}

// Collective: the exchange's device link, the first forces.
std::unique_ptr<Simulation> start(const SceneSpec& scene, const RunRequest& a, Transport& transport,
                                  std::shared_ptr<DomainExchange> split, const std::optional<RestartState>& restart,
                                  bool own_gpu) {
  RunOptions options;
  options.backend = a.backend;
  std::shared_ptr<DomainExchange> exchange = split ? with_link(split, a, transport, own_gpu) : nullptr;
  if (!restart) return std::make_unique<Simulation>(scene, options, exchange);
  return std::make_unique<Simulation>(scene, options, exchange, *restart);
}

// Rank k of K: the stored positions of particles [k N / K, (k+1) N / K).
std::vector<Vec3d> checkpoint_position_share(const std::string& path, const Transport& transport) {
  const std::size_t n = checkpoint_particle_count(path), k = std::size_t(transport.rank()),
                    ranks = std::size_t(transport.size());
  std::vector<Vec3d> share;
  for_each_checkpoint_position_block(path, n * k / ranks, n * (k + 1) / ranks,
                                     [&](std::size_t, const std::vector<Vec3d>& x) {
                                       share.insert(share.end(), x.begin(), x.end());
                                     });
  return share;
}

// Ranks that read their checkpoint from different copies (node-local
// scratch) must have read the same step.
void expect_same_step_everywhere(Transport& transport, const std::string& path, long long step) {
  const Bytes first = transport.broadcast(Bytes(reinterpret_cast<const char*>(&step),
                                                reinterpret_cast<const char*>(&step) + sizeof(step)), 0);
  long long step_0 = 0;
  std::memcpy(&step_0, first.data(), sizeof(step_0));
  throw_if_any_failed(transport, step == step_0 ? "" : "checkpoint " + path + " is at step " + std::to_string(step) +
                                                          ", rank 0's at step " + std::to_string(step_0));
}

// A restart continues the checkpoint's steps: the run must end at or after
// its step, and go on at its time step (a run's time is its step times the
// time step, so the checkpoint's is its time over its step), else its time
// would jump and its end be counted in other steps (an edited scene whose
// materials or stiffness changed the step computed from the contact time).
void check_restart_steps(const RestartState& r, const SceneSpec& scene, const RunRequest& a, long long total) {
  if (total < r.step) {
    const std::string end = a.steps >= 0 ? "--steps " + std::to_string(total)
                                          : "the scene's duration (step " + std::to_string(total) + ")";
    throw std::invalid_argument(end + " ends before the checkpoint's step " + std::to_string(r.step) +
                                ": --steps is the step to end at, counted from the run's start");
  }
  if (r.step == 0) return;
  const double then = r.time / double(r.step);
  if (std::abs(scene.time_step - then) <= 1e-9 * then) return;
  char text[256];
  std::snprintf(text, sizeof(text),
                "the scene's time step %.17g s differs from the checkpoint's %.17g s (its time over its step): a "
                "restart continues the checkpoint's steps, so set time_step: {absolute: %.17g} to go on",
                scene.time_step, then, then);
  throw std::invalid_argument(text);
}

// SIGTERM/SIGUSR1 read at every step without waiting on the slowest rank:
// each step completes the reduction the step before started (done by then)
// and starts the next, so every rank learns of a signal to any rank at the
// same step, at most two steps after it arrived. A batch system, or mpiexec,
// kills the ranks a fixed time after the signal, whatever the length of a step
// or of a chunk between outputs.
class StopAgreement {
 public:
  StopAgreement(Transport& transport, std::function<bool()> stop_requested)
      : transport_(transport), stop_requested_(std::move(stop_requested)) {}
  StopAgreement(const StopAgreement&) = delete;
  StopAgreement& operator=(const StopAgreement&) = delete;
  ~StopAgreement() {
    try {
      settle();
    } catch (...) {  // the run is ending with an error already
    }
  }
  // After each step (collective): true when the run must stop now.
  bool after_step() {
    if (settle()) return true;
    transport_.start_min(stop_requested_ && stop_requested_() ? 0 : 1);
    pending_ = true;
    return false;
  }
  // Completes the outstanding reduction, so none is left across the other
  // collectives between steps; true once any rank has asked to stop.
  bool settle() {
    if (pending_) {
      pending_ = false;
      stopped_ = transport_.finish_min() == 0 || stopped_;
    }
    return stopped_;
  }

 private:
  Transport& transport_;
  std::function<bool()> stop_requested_;  // this rank's signal; may be empty
  bool pending_ = false, stopped_ = false;
};

int advance(const SceneSpec& scene, const RunRequest& a, Transport& transport, Simulation& sim, RunOutput& out,
            RunMeasurements& measurements, long long total, long long particles) {
  RankExchange* exchange = sim.exchange();
  const long long every = scene.output.interval > 0 ? steps_per(scene.output.interval, scene.time_step) : total;
  const long long checkpoint_every = steps_per(scene.output.checkpoint_interval, scene.time_step);
  const double checkpoint_seconds = 60.0 * scene.output.checkpoint_minutes;
  const bool checkpointing = checkpoint_every > 0 || checkpoint_seconds > 0;
  // Mixing analysis at start, start + every, ...
  const Schedule mixing = scene.mixing ? Schedule{scene.mixing->start, scene.mixing->every, scene.time_step}
                                       : Schedule{};
  // Marking is a function of the positions at its step, so doing it again
  // after a restart at that very step changes nothing.
  const long long mark_step = scene.marking ? std::llround(scene.marking->time / scene.time_step) : -1;
  auto mark_if_due = [&](long long step) {
    if (step != mark_step) return;
    sim.mark(*scene.marking);
    out.log("step %lld: particles marked %d / %d by their side of the plane\n", step, int(scene.marking->front),
            int(scene.marking->back));
  };
  const bool removes = scene.has_exits();
  const auto t0 = Clock::now();
  auto last_checkpoint = t0;
  const long long first_step = sim.step_count();  // after a restart, the rate counts this run's steps only
  Progress progress(first_step, total, particles, transport.rank() == 0);
  StopAgreement stop_signal(transport, a.stop_requested);
  std::unique_ptr<InsertionLog> inserted;
  if (!scene.inlets.empty()) inserted = std::make_unique<InsertionLog>(scene, out.directory(), transport);
  sim.check_fault();  // in the first forces
  if (a.restart.empty()) mark_if_due(0);
  if (a.restart.empty()) out.snapshot(sim);
  if (a.restart.empty() && mixing.due(0)) out.mixing(sim);
  if (a.restart.empty()) {
    measurements.prepare(sim, 0);
    measurements.evaluate(sim);
  }
  while (sim.step_count() < total) {
    const long long step = sim.step_count();
    long long chunk = std::min({every > 0 ? every - step % every : total, total - step, 200LL});
    if (checkpoint_every > 0) chunk = std::min(chunk, checkpoint_every - step % checkpoint_every);
    if (mixing.every > 0) chunk = std::min(chunk, mixing.next_after(step) - step);
    if (mark_step > step) chunk = std::min(chunk, mark_step - step);
    if (const long long due = measurements.next_due_after(step); due > step) chunk = std::min(chunk, due - step);
    measurements.prepare(sim, step + chunk);
    sim.run(chunk, [&] { return stop_signal.after_step(); });
    if (removes) out.removals(sim);  // before any output, so that a checkpoint's removals are in removed.csv
    if (inserted) inserted->write(sim.take_insertion_records(), [&](const std::string& line) { out.log("%s", line.c_str()); });
    if (removes || inserted) particles = exchange ? exchange->total(sim.particle_count()) : sim.particle_count();
    mark_if_due(sim.step_count());
    progress.update(sim, particles);
    const long long now = sim.step_count();
    // A checkpoint known to follow takes the snapshot's host copy as it is,
    // which must then hold the forces too (a wall-clock one or a stop
    // copies them itself).
    const bool checkpoint_follows = (checkpoint_every > 0 && now % checkpoint_every == 0) || (checkpointing && now == total);
    if ((every > 0 && now % every == 0) || now == total) out.snapshot(sim, checkpoint_follows);
    if (mixing.due(now)) out.mixing(sim);
    measurements.evaluate(sim);
    const bool wall_due = checkpoint_seconds > 0 &&
                          seconds_since(last_checkpoint) >= checkpoint_seconds;
    // Every rank must agree before a collective checkpoint or a stop.
    const bool stop = stop_signal.settle();
    const bool due = checkpoint_follows || transport.min(wall_due ? 0 : 1) == 0;
    if (due || stop) {
      measurements.evaluate(sim, true);
      out.checkpoint(sim);
      last_checkpoint = Clock::now();
    }
    if (stop) {
      out.finish();
      out.log("stopped by a signal at step %lld (t = %.6g s): the run is not complete; restart with --restart\n", now,
              sim.time());
      return 3;
    }
  }
  out.finish();  // the output is part of the run's time
  const double wall = seconds_since(t0);
  out.log("done: %lld steps, t = %.6g s, %.3g particle-steps/s\n", total, sim.time(), progress.rate());
  if (removes) out.log("particles at the end: %lld\n", particles);
  if (exchange) out.log("decomposition at the end: %s\n", exchange->describe().c_str());
  out.log("%s", measurements.cost_summary(sim).c_str());
  const StepTimings t = sim.timings();
  out.log("time per phase (s, rank 0): integration %.3f, neighbour build %.3f, contact forces %.3f, exchange %.3f, "
          "output %.3f, total wall %.3f\n",
          t.integrate, t.neighbours, t.forces, t.exchange, wall - (t.integrate + t.neighbours + t.forces + t.exchange),
          wall);
  const RunOutput::Split o = out.split();
  out.log("output split (s, rank 0): waiting for the writer %.3f, host copies %.3f, wall contacts %.3f, mesh loads "
          "%.3f, time series %.3f\n",
          o.waiting, o.host_copy, o.wall_records, o.mesh_loads, o.series);
  out.log("neighbour lists built %lld times in %lld steps (rank 0)\n", sim.neighbour_builds(), total - first_step);
  if (exchange) {
    const ExchangeSplit x = exchange->split();
    const double sum = x.total() > 0 ? x.total() : 1;
    out.log("exchange split (rank 0, timed steps): route %.0f%%, pack %.0f%%, transfer and waiting %.0f%%, "
            "unpack %.0f%%; halo rebuilt %lld times, forwarded %lld times\n", 100 * x.route / sum, 100 * x.pack / sum,
            100 * x.transfer / sum, 100 * x.unpack / sum, x.rebuilds, x.forwards);
  }
  const double peak = double(backend_peak_bytes(sim.backend()));
  const double reserved = double(backend_reserved_peak_bytes(sim.backend()));
  const double owned = sim.particle_count() > 0 ? double(sim.particle_count()) : 1.0;
  // What the GPU's pool held from the driver at most, where that differs (backend/memory.hpp).
  char pool[96] = "";
  if (reserved != peak)
    std::snprintf(pool, sizeof pool, " (the pool held at most %s, %.1f)", human_bytes(reserved).c_str(), reserved / owned);
  out.log("peak %s memory (rank 0): %s, %.1f bytes per owned particle%s\n", backend_name(sim.backend()),
          human_bytes(peak).c_str(), peak / owned, pool);
  return 0;
}

}  // namespace

std::unique_ptr<Simulation> start_scene(SceneSpec& scene, const SceneStart& start, Transport& transport) {
  RunRequest request;
  request.backend = start.options.backend;
  request.exchange = start.exchange;
  bool own_gpu = false;
  on_every_rank(transport, [&] {
    if (start.exchange != "auto" && start.exchange != "device" && start.exchange != "host")
      throw std::invalid_argument("exchange must be auto, device or host, got " + start.exchange);
    own_gpu = start.options.backend == Backend::cuda && select_cuda_device(transport.local_rank());
  });
  scene.kept_blocks = std::make_shared<KeptFillBlocks>(kept_blocks_budget(1 - transport.min(-transport.local_rank())));
  if (start.check_packing) check_fit_on_ranks(scene, transport);
  std::shared_ptr<DomainExchange> split;
  if (transport.size() > 1) on_every_rank(transport, [&] { split = split_scene(scene, transport); });
  if (start.check_packing) check_overlaps_on_ranks(scene, transport, split.get());
  std::shared_ptr<DomainExchange> exchange = split ? with_link(split, request, transport, own_gpu) : nullptr;
  auto sim = std::make_unique<Simulation>(scene, start.options, exchange);
  scene.kept_blocks.reset();
  return sim;
}

int run_scene(const RunRequest& request, Transport& transport) {
  // Each phase a rank can fail alone ends with every rank agreeing on it.
  const RunRequest& a = request;
  const auto setup_start = Clock::now();
  std::optional<SceneSpec> loaded;
  std::string text;
  std::uint64_t hash = 0;
  on_every_rank(transport, [&] {
    check_request(a);
    loaded = load_scene(a.scene, PackingChecks::by_caller);  // below, each rank over its own particles
    text = file_text(a.scene);
    hash = scene_hash(text);
  });
  const SceneSpec& scene = *loaded;
  expect_same_run_everywhere(transport, a, hash, scene);
  if (transport.rank() == 0) print_warnings(scene);
  const std::string directory = a.out.empty() ? scene.output.directory : a.out;
  // Only rank 0 writes, so only its view of the directory counts.
  on_every_rank(transport, [&] {
    if (transport.rank() == 0) check_output_directory(directory, directory_use(a));
  });
  const long long total = a.steps >= 0 ? a.steps : std::llround(scene.duration / scene.time_step);
  bool own_gpu = false;
  std::optional<RestartState> restart;
  std::shared_ptr<DomainExchange> split;
  // A restart on several ranks: each rank reads its share of the stored
  // positions for the split, then only the particles it owns.
  std::vector<Vec3d> share;
  on_every_rank(transport, [&] {
    own_gpu = a.backend == Backend::cuda && select_cuda_device(transport.local_rank());
    if (!a.restart.empty() && transport.size() > 1) share = checkpoint_position_share(a.restart, transport);
  });
  const double load_seconds = seconds_since(setup_start);
  // A new run's fill blocks are made once on each rank: kept from the fit
  // check through the split and the overlap check to the upload.
  if (a.restart.empty()) {
    loaded->kept_blocks = std::make_shared<KeptFillBlocks>(kept_blocks_budget(1 - transport.min(-transport.local_rank())));
    check_fit_on_ranks(scene, transport);
  }
  const double check_seconds = seconds_since(setup_start) - load_seconds;
  // The split's one collective (summing the counts) comes before anything
  // in it can fail, so every rank reaches it (the fit check made its blocks).
  if (transport.size() > 1)
    on_every_rank(transport, [&] {
      split = a.restart.empty() ? split_scene(scene, transport) : split_restart(scene, transport, share);
    });
  share = {};
  const double split_seconds = seconds_since(setup_start) - load_seconds - check_seconds;
  const auto overlap_start = Clock::now();
  if (a.restart.empty()) check_overlaps_on_ranks(scene, transport, split.get());
  const double packing_seconds = check_seconds + seconds_since(overlap_start);
  std::optional<EditedRestart> edits;
  std::string stored_text;  // the edited restart's checkpoint's scene text
  std::uint64_t stored_hash = 0;
  on_every_rank(transport, [&] {
    if (a.restart.empty()) return;
    CheckpointExpectations expect;
    if (!a.edited_scene) expect.scene_hash = hash;
    std::function<bool(const Vec3d&)> keep;
    if (split) keep = [&split](const Vec3d& x) { return split->owns(x); };
    Checkpoint c = read_checkpoint(a.restart, expect, keep);
    restart = restart_state(c);
    if (!a.edited_scene) return;
    stored_hash = c.scene_hash;
    stored_text = std::move(c.scene_text);
    const std::vector<Wall> stored_walls = std::move(c.walls);
    c = {};
    edits = adapt_to_edited_scene(*restart, stored_walls, scene);
  });
  if (restart) {
    expect_same_step_everywhere(transport, a.restart, restart->step);
    // The same on every rank (the step just agreed, the command line checked),
    // before the output directory drops what followed the checkpoint.
    on_every_rank(transport, [&] { check_restart_steps(*restart, scene, a, total); });
  }
  // Collective from here on: an error on one rank alone in the middle of an
  // exchange can only be reported by ending every rank (main.cpp).
  std::unique_ptr<Simulation> sim = start(scene, a, transport, split, restart, own_gpu);
  restart.reset();  // the simulation holds the state now
  loaded->particles = {};  // and this rank's own particles
  loaded->kept_blocks.reset();
  const double setup_seconds = seconds_since(setup_start);
  RankExchange* exchange = sim->exchange();
  std::unique_ptr<RunOutput> output;
  std::unique_ptr<RunMeasurements> measurements;
  on_every_rank(transport, [&] {
    if (transport.rank() == 0) prepare_output_directory(directory, directory_use(a), scene, sim->step_count());
    output = std::make_unique<RunOutput>(scene, directory, transport, text);
    measurements = std::make_unique<RunMeasurements>(scene, directory, transport);
  });
  RunOutput& out = *output;
  const long long particles =
      exchange ? exchange->total(sim->particle_count()) : sim->particle_count();
  out.log("grainstorm %s: %s, %lld particles, backend %s, %d rank%s, dt = %.4g s (contact time %.4g s), steps %lld to %lld\n",
          GS_VERSION, a.scene.c_str(), particles, backend_name(a.backend), transport.size(),
          transport.size() > 1 ? "s" : "", scene.time_step, scene.contact_time, sim->step_count(), total);
  const Simulation::SetupTimings& st = sim->setup_timings();
  out.log("set up in %.2f s (scene %.2f s, packing checks %.2f s, decomposition %.2f s, particles %.2f s, first "
          "forces %.2f s)\n",
          setup_seconds, load_seconds, packing_seconds, split_seconds, st.particles, st.first_forces);
  const HostThreads host = host_threads();
  out.log("host threads (rank 0): %d on %d core%s\n", host.threads, host.cores, host.cores > 1 ? "s" : "");
  if (host.threads > host.cores)
    out.log("warning: %d host threads share %d core%s (rank 0's CPU affinity): set-up, output and the cpu backend "
            "run slower; start ranks with cores of their own (mpirun --bind-to none, or --map-by ...:PE=n)\n",
            host.threads, host.cores, host.cores > 1 ? "s" : "");
  if (!a.restart.empty()) {
    out.resume(sim->step_count());
    measurements->resume(*sim);
    out.log("restarted from %s at step %lld\n", a.restart.c_str(), sim->step_count());
  }
  if (edits) {
    const std::size_t dropped = summed_over_ranks(transport, *edits);
    for (const std::string& line :
         edited_restart_lines(*edits, dropped, stored_hash, hash, stored_text, text, scene.wall_names.size()))
      out.log("%s\n", line.c_str());
  }
  if (exchange) out.log("decomposition: %s\n", exchange->describe().c_str());
  try {
    return advance(scene, a, transport, *sim, out, *measurements, total, particles);
  } catch (const SimulationFault& fault) {
    // Every rank has the same fault (agreed in check_fault): log it and keep
    // the state it was found in.
    out.log("run stopped by a fault: %s\n", fault.what());
    out.removals(*sim);  // what left before it
    out.fault_snapshot(*sim);
    throw;
  } catch (const RankFailure& failure) {  // an output rank 0 could not write
    out.log("run stopped by an error: %s\n", failure.what());
    throw;
  }
}

}  // namespace gs
