// Where the time of a snapshot and a checkpoint goes, on one rank: a
// frictional lattice bed of N touching spheres (so every particle has contact
// history), one step, then each part of the output path timed on its own and
// the whole path as a run takes it (comm/ + run/RunOutput).
//
//   output_bench --n N --dir DIR [--backend cpu|cuda]
//
// Prints one line of key=value: seconds per part, file sizes and GB/s
// (bytes of the file over the seconds the run waited, and over the seconds
// until the file was complete).
#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

#include "comm/transport.hpp"
#include "contact/contact_models.hpp"
#include "engine/simulation.hpp"
#include "io/checkpoint.hpp"
#include "io/h5_snapshot.hpp"
#include "io/restart.hpp"
#include "run/run_output.hpp"
#include "scene/scene_time_step.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// CPU seconds of the whole process (every thread): on a loaded machine a
// fairer measure of the work than the wall time.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

std::string cpu_log;  // "name_cpu_s=..." for each timed part

template <class F>
double timed(const char* name, F&& f) {
  const auto t = Clock::now();
  const double c = cpu_seconds();
  f();
  char text[96];
  std::snprintf(text, sizeof(text), " %s_cpu_s=%.3f", name, cpu_seconds() - c);
  cpu_log += text;
  return seconds_since(t);
}

gs::Wall plane(gs::Vec3d point, gs::Vec3d normal) {
  gs::Wall w;
  w.kind = gs::WallKind::plane;
  w.point = point;
  w.normal = normal;
  return w;
}

// Glass-like spheres of 1 mm on a square lattice, pressed 0.5 % into contact.
gs::SceneSpec bed_scene(long long n, const std::string& dir) {
  const double r = 1e-3, spacing = 2 * r * 0.995;
  const long long side = std::llround(std::cbrt(double(n) / 2));
  const long long layers = (n + side * side - 1) / (side * side);
  gs::SceneSpec s;
  s.path = "output_bench";
  s.effects = gs::kFriction;
  s.gravity = {0, 0, -9.81};
  const double width = double(side) * spacing + 2 * r, height = double(layers) * spacing + 4 * r;
  s.domain_min = {-r, -r, -r};
  s.domain_max = {width + r, width + r, height + r};
  s.materials.push_back({"glass", 2500, 6e7, 0.25});
  gs::PairSpec p;
  p.stiffness_normal = 2e3;
  p.stiffness_tangential = p.stiffness_normal * 2 / 7;
  p.restitution = 0.5;
  p.friction = 0.5;
  s.pairs.push_back(p);
  s.walls = {plane({0, 0, 0}, {1, 0, 0}), plane({width, 0, 0}, {-1, 0, 0}), plane({0, 0, 0}, {0, 1, 0}),
             plane({0, width, 0}, {0, -1, 0}), plane({0, 0, 0}, {0, 0, 1}), plane({0, 0, height}, {0, 0, -1})};
  const double lo = r + 1e-6;
  for (long long k = 0; k < n; ++k) {
    gs::ParticleInit q;
    q.id = gs::ParticleId(k);
    q.radius = r;
    q.position = {lo + double(k % side) * spacing, lo + double((k / side) % side) * spacing,
                  lo + double(k / (side * side)) * spacing};
    s.particles.push_back(q);
  }
  s.contact_time = gs::critical_contact_time(s);
  s.time_step = 0.1 * s.contact_time;  // within the stability limit (settle_bench's step)
  s.duration = s.time_step * 10;
  s.output.directory = dir;
  return s;
}

double gigabytes(const std::string& path) { return double(std::filesystem::file_size(path)) / 1e9; }

}  // namespace

int main(int argc, char** argv) {
  try {
    long long n = 1000000;
    std::string dir = "/tmp/output_bench";
    gs::RunOptions options{gs::default_backend()};
    for (int k = 1; k + 1 < argc; k += 2) {
      const std::string a = argv[k], v = argv[k + 1];
      if (a == "--n") n = std::stoll(v);
      else if (a == "--dir") dir = v;
      else if (a == "--backend") options.backend = gs::parse_backend(v);
      else throw std::invalid_argument("unknown option " + a);
    }
    std::filesystem::create_directories(dir);
    const gs::SceneSpec scene = bed_scene(n, dir);
    gs::Simulation sim(scene, options);
    sim.run(1);
    gs::ParticleSnapshot s;
    gs::HostHistory h;
    const double t_snapshot = timed("snapshot", [&] { s = sim.snapshot(); });
    const double t_history = timed("history", [&] { h = sim.history(); });
    const std::string snap = dir + "/bench_snapshot.h5", check = dir + "/bench_checkpoint.h5";
    gs::SnapshotMetadata m;
    const double t_write_snapshot =
        timed("write_snapshot", [&] { gs::write_snapshot(snap, s, gs::default_snapshot_fields(), sim.walls(), m); });
    const double snapshot_gb = gigabytes(snap);
    gs::Checkpoint c;
    const double t_make_checkpoint =
      timed("make_checkpoint", [&] { c = gs::make_checkpoint(std::move(s), std::move(h), sim.walls(), 0, 1); });
    const double t_checksum = timed("checksum", [&] { (void)gs::checkpoint_checksum(c); });
    const double t_write_checkpoint = timed("write_checkpoint", [&] { gs::write_checkpoint(check, c); });
    const double checkpoint_gb = gigabytes(check);
    c = gs::Checkpoint();
    std::filesystem::remove(snap);
    std::filesystem::remove(check);
    // The whole path, as the run's driver takes it: the wait of the step, then
    // the time until the files are complete.
    const std::unique_ptr<gs::Transport> transport = gs::make_single_transport();
    double run_snapshot = 0, run_checkpoint = 0, run_complete = 0;
    {
      gs::RunOutput out(scene, dir, *transport, "");
      const auto t = Clock::now();
      run_snapshot = timed("run_snapshot_wait", [&] { out.snapshot(sim); });
      run_checkpoint = timed("run_checkpoint_wait", [&] { out.checkpoint(sim); });
      out.finish();
      run_complete = seconds_since(t);
    }
    std::printf("backend=%s n=%zu snapshot_s=%.3f history_s=%.3f write_snapshot_s=%.3f snapshot_gb=%.3f "
                "make_checkpoint_s=%.3f checksum_s=%.3f write_checkpoint_s=%.3f checkpoint_gb=%.3f "
                "run_snapshot_wait_s=%.3f run_checkpoint_wait_s=%.3f run_both_complete_s=%.3f "
                "snapshot_write_gbps=%.3f checkpoint_write_gbps=%.3f run_gbps_complete=%.3f%s\n",
                gs::backend_name(options.backend), scene.particles.size(), t_snapshot, t_history, t_write_snapshot,
                snapshot_gb, t_make_checkpoint, t_checksum, t_write_checkpoint, checkpoint_gb, run_snapshot,
                run_checkpoint, run_complete, snapshot_gb / (t_snapshot + t_write_snapshot),
                checkpoint_gb / (t_snapshot + t_history + t_make_checkpoint + t_write_checkpoint),
                (snapshot_gb + checkpoint_gb) / run_complete, cpu_log.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "output_bench: %s\n", e.what());
    return 1;
  }
}
