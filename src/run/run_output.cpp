#include "run/run_output.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <utility>

#include "analysis/block_sum.hpp"
#include "analysis/mixing.hpp"
#include "contact/contact_models.hpp"
#include "analysis/wall_loads.hpp"
#include "comm/rank_agreement.hpp"
#include "comm/snapshot_gather.hpp"
#include "core/wall_clock.hpp"
#include "io/fnv1a.hpp"
#include "io/h5_io.hpp"
#include "io/h5_meshes.hpp"
#include "io/h5_snapshot.hpp"
#include "io/particle_csv.hpp"
#include "io/restart.hpp"
#include "io/text_file.hpp"

namespace gs {
namespace {

std::string fault_snapshot_name(long long step) {
  char name[64];
  std::snprintf(name, sizeof(name), "fault_%010lld.h5", step);
  return name;
}

}  // namespace

RunOutput::RunOutput(const SceneSpec& scene, const std::string& directory, Transport& transport,
                     std::string scene_text)
    : scene_(scene),
      directory_(directory),
      transport_(transport),
      scene_text_(std::move(scene_text)),
      scene_hash_(scene_hash(scene_text_)) {
  fields_ = scene.output.fields.empty() ? default_snapshot_fields() : parse_snapshot_fields(scene.output.fields);
  if (fields_.has(SnapshotField::contact_count) && !keeps_history(scene.model, scene.effects))
    throw std::invalid_argument("output.fields: contact_count needs a contact history (friction, rolling resistance "
                                "or the hysteretic_linear contact model)");
  // A periodic run's positions are wrapped: the image counts unwrap them.
  if (particle_fields_kept(scene) & kImageCounts) fields_.add(SnapshotField::image);
  if (transport_.rank() != 0) return;
  std::error_code made;
  std::filesystem::create_directories(directory_, made);
  if (made) throw std::runtime_error("cannot create the output directory " + directory_ + ": " + made.message());
  log_ = open_for_writing(directory_ + "/run.log", "a");
  timeseries_ = open_for_writing(directory_ + "/timeseries.csv", "a");
  if (scene.mixing) {
    const std::filesystem::path log_path(scene.mixing->output);
    mixing_log_ = std::make_unique<MixingLog>(
        *scene.mixing, log_path.is_absolute() ? log_path.string() : directory_ + "/" + log_path.string());
  }
  if (scene.has_exits()) {
    std::vector<std::string> materials;
    for (const MaterialSpec& m : scene.materials) materials.push_back(m.name);
    removal_log_ = std::make_unique<RemovalLog>(directory_ + "/removed.csv",
                                                exits_of(scene.outlets, scene.open_faces).names, materials,
                                                scene.time_step);
  }
  if (std::ftell(timeseries_) == 0) {
    std::fprintf(timeseries_, "step,time,particles,kinetic_energy_translational,kinetic_energy_rotational,"
                              "max_speed,contacts");
    // Load of the particles on each wall and mesh: force, torque about its rotation centre.
    for (std::size_t k = 0; k < scene.walls.size(); ++k)
      for (const char* c : {"fx", "fy", "fz", "tx", "ty", "tz"})
        std::fprintf(timeseries_, ",wall_%s_%s",
                     k < scene.wall_names.size() ? scene.wall_names[k].c_str() : std::to_string(k).c_str(), c);
    for (std::int32_t k = 0; k < scene.meshes.n_meshes(); ++k)
      for (const char* c : {"fx", "fy", "fz", "tx", "ty", "tz"}) std::fprintf(timeseries_, ",mesh%d_%s", int(k), c);
    std::fprintf(timeseries_, "\n");
  }
}

RunOutput::~RunOutput() {
  // A run that ends by an exception still leaves complete files (or none).
  const std::string error = writer_.wait();
  if (!error.empty()) std::fprintf(stderr, "output not written: %s\n", error.c_str());
  if (log_) std::fclose(log_);
  if (timeseries_) std::fclose(timeseries_);
}

void RunOutput::log(const char* format, ...) {
  if (transport_.rank() != 0) return;
  const std::lock_guard<std::mutex> lock(log_mutex_);  // the writer's thread logs too
  for (std::FILE* f : {stdout, log_}) {
    std::va_list args;
    va_start(args, format);
    std::vfprintf(f, format, args);
    va_end(args);
    std::fflush(f);
  }
}

// "checkpoint: out/checkpoint_0000001000.h5 (1.96 GB written in 2.10 s, 0.93 GB/s)"
void RunOutput::log_written(const char* what, const std::string& path, double seconds) {
  const double gigabytes = double(std::filesystem::file_size(path)) / 1e9;
  log("%s: %s (%.3g GB written in %.3g s, %.3g GB/s)\n", what, path.c_str(), gigabytes, seconds,
      seconds > 0 ? gigabytes / seconds : 0.0);
}

void RunOutput::finish() {
  const auto start = Clock::now();
  std::string error;
  if (transport_.rank() == 0) error = writer_.wait();
  throw_if_any_failed(transport_, error);
  split_.waiting += seconds_since(start);
}

namespace {
// A time-series row's sums over the particles, in fixed blocks on every
// host thread (analysis/block_sum.hpp): the same bits whatever the threads
// and ranks.
struct SeriesSums {
  double translational = 0, rotational = 0, max_speed = 0;
  long long contacts = 0;
};

SeriesSums series_sums(const ParticleSnapshot& s, bool with_contacts) {
  return sum_in_blocks(
      s.size(), SeriesSums{},
      [&](SeriesSums& a, std::size_t i) {
        a.translational += 0.5 * s.mass[i] * norm2(s.velocity[i]);
        a.rotational += 0.5 * s.inertia[i] * norm2(s.angular_velocity[i]);
        a.max_speed = std::max(a.max_speed, norm(s.velocity[i]));
        if (with_contacts) a.contacts += s.contacts[i];
      },
      [](SeriesSums& total, const SeriesSums& block) {
        total.translational += block.translational;
        total.rotational += block.rotational;
        total.max_speed = std::max(total.max_speed, block.max_speed);
        total.contacts += block.contacts;
      });
}

// The seconds since `t`, which moves on to now: consecutive parts of a call.
double lap(Clock::time_point& t) {
  const Clock::time_point now = Clock::now();
  const double seconds = std::chrono::duration<double>(now - t).count();
  t = now;
  return seconds;
}
}  // namespace

void RunOutput::in_background(std::function<void()> job) {
  if (transport_.rank() == 0) writer_.start(std::move(job));
}

void RunOutput::snapshot(const Simulation& sim, bool checkpoint_follows) {
  finish();  // the previous files are complete before the host copy is refilled
  auto t = Clock::now();
  std::vector<double> mesh_load;  // per mesh: fx fy fz tx ty tz, summed over ranks (collective)
  for (const MeshLoad& l : sim.mesh_loads())
    mesh_load.insert(mesh_load.end(), {l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z});
  if (!mesh_load.empty()) transport_.sum(mesh_load);  // every rank has the same meshes
  split_.mesh_loads += lap(t);
  stage(sim, false,
        checkpoint_follows || fields_.has(SnapshotField::force) || fields_.has(SnapshotField::torque));
  split_.host_copy += lap(t);
  const ParticleSnapshot& s = staged_.particles;
  // The particles on a wall, with their history, into arrays kept from the
  // last output; every rank's on rank 0.
  const bool need_history = keeps_history(scene_.model, scene_.effects);
  if (need_history) sim.wall_contact_history_into(on_walls_, pins_);
  else on_walls_ = ParticleRecords{};
  const bool one_rank = transport_.size() == 1;
  ParticleRecords gathered;
  if (!one_rank) gathered = gather_history_records(transport_, on_walls_);
  const ParticleRecords& on_walls = one_rank ? on_walls_ : gathered;
  split_.wall_records += lap(t);
  written_by_rank_0(transport_, [&] { write_timeseries_row(sim, s, on_walls, mesh_load); });
  split_.series += lap(t);
  // The files themselves while the run steps on; the job reads staged_,
  // which the next snapshot or checkpoint refills only after finish().
  in_background([this, walls = sim.walls(), meshes = sim.meshes()] {
    write_snapshot_files(staged_.particles, walls, meshes);
  });
  writing_history_ = false;
}

// This rank's owned particles (and their contact history) to the host, and
// every rank's in staged_ on rank 0. One rank fills staged_ directly; more
// fill their local_ arrays first. Either way into arrays kept from the last
// output: no fresh memory to fault in, and on a GPU pinned once.
void RunOutput::stage(const Simulation& sim, bool with_history, bool with_forces) {
  const bool one_rank = transport_.size() == 1;
  ParticleSnapshot& mine = one_rank ? staged_.particles : local_;
  staged_from_ = StagedState{};  // until the copy is complete
  sim.snapshot_into(mine, pins_, with_forces);
  if (with_history) stage_history(sim);
  gather_snapshot(transport_, mine, staged_.particles);
  staged_from_ = StagedState{&sim, sim.step_count(), sim.particle_count(), with_forces};
}

// The history in the particles' order: this rank's, and every rank's on rank 0.
void RunOutput::stage_history(const Simulation& sim) {
  const bool one_rank = transport_.size() == 1;
  HostHistory& history = one_rank ? staged_.history : local_history_;
  sim.history_into(history, pins_);
  gather_history(transport_, (one_rank ? staged_.particles : local_).id, history, staged_.history);
}

bool RunOutput::staged_particles_are(const Simulation& sim) const {
  return staged_from_.sim == &sim && staged_from_.step == sim.step_count() &&
         staged_from_.owned == sim.particle_count() && staged_from_.forces;
}

// On the writer's thread: the snapshot's files, then the indexes that name
// them, so that an index never names a file that is not complete.
void RunOutput::write_snapshot_files(const ParticleSnapshot& s, const std::vector<Wall>& walls, const MeshSet& meshes) {
  if (scene_.output.format == "csv") {
    write_particles_csv(directory_ + "/" + snapshot_file_name(s.step), s);
    return;
  }
  SnapshotMetadata m;
  m.scene_hash = scene_hash_;
  m.scene_path = scene_.path;
  m.wall_names = scene_.wall_names;
  if (fields_.has(SnapshotField::contact_count))
    m.contact_count = keeps_history(scene_.model, scene_.effects) ? s.contacts : std::vector<std::uint16_t>(s.size(), 0);
  m.domain = DomainBox{scene_.domain_min, scene_.domain_max};
  const std::string name = snapshot_h5_name(s.step);
  const auto start = Clock::now();
  write_snapshot(directory_ + "/" + name, s, fields_, walls, m);
  log_written("snapshot", directory_ + "/" + name, seconds_since(start));
  series_.push_back(xdmf_entry(name, s, fields_, read_snapshot_wall_surfaces(directory_ + "/" + name)));
  write_xdmf_series(directory_ + "/particles.xdmf", series_);
  if (meshes.n_triangles() > 0) {
    const std::string mesh_file = meshes_h5_name(s.step);
    write_meshes_h5(directory_ + "/" + mesh_file, meshes, s.time, s.step);
    mesh_series_.push_back({s.time, mesh_file, std::size_t(meshes.n_vertices()), std::size_t(meshes.n_triangles())});
    write_mesh_xdmf(directory_ + "/meshes.xdmf", mesh_series_);
  }
}

void RunOutput::write_timeseries_row(const Simulation& sim, const ParticleSnapshot& s, const ParticleRecords& on_walls,
                                     const std::vector<double>& mesh_load) {
  const bool need_history = keeps_history(scene_.model, scene_.effects);
  const SeriesSums sums = series_sums(s, need_history);
  std::fprintf(timeseries_, "%lld,%.17g,%zu,%.17g,%.17g,%.17g,%lld", s.step, s.time, s.size(), sums.translational,
               sums.rotational, sums.max_speed, need_history ? sums.contacts : -1LL);
  for (const MeshLoad& l : wall_loads(scene_, sim.walls(), s, on_walls))
    for (double x : {l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z})
      std::fprintf(timeseries_, ",%.17g", x);
  for (double x : mesh_load) std::fprintf(timeseries_, ",%.17g", x);
  std::fprintf(timeseries_, "\n");
  flush_checked(timeseries_, directory_ + "/timeseries.csv");
}

void RunOutput::mixing(const Simulation& sim) {
  const ParticleSnapshot s = gather_snapshot(transport_, sim.snapshot());
  written_by_rank_0(transport_, [&] {
    if (mixing_log_) mixing_log_->append(evaluate_mixing(*scene_.mixing, s));
  });
}

void RunOutput::removals(Simulation& sim) {
  if (!scene_.has_exits()) return;
  const std::vector<RemovedParticle> mine = sim.take_removed();
  Bytes local(mine.size() * sizeof(RemovedParticle));
  if (!mine.empty()) std::memcpy(local.data(), mine.data(), local.size());
  const std::vector<Bytes> every_rank = transport_.gather(std::move(local));
  written_by_rank_0(transport_, [&] {
    std::vector<RemovedParticle> all;
    for (const Bytes& b : every_rank) {
      const std::size_t at = all.size();
      all.resize(at + b.size() / sizeof(RemovedParticle));
      if (!b.empty()) std::memcpy(all.data() + at, b.data(), b.size());
    }
    removal_log_->append(std::move(all));
  });
}

void RunOutput::resume(long long step) {
  finish();
  written_by_rank_0(transport_, [&] { index_earlier_snapshots(step); });
}

void RunOutput::index_earlier_snapshots(long long step) {
  if (scene_.output.format != "hdf5") return;
  std::vector<std::pair<long long, std::string>> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory_)) {
    const std::string name = entry.path().filename().string();
    long long s = -1;
    if (std::sscanf(name.c_str(), "particles_%lld.h5", &s) == 1 && name == snapshot_h5_name(s) && s <= step)
      files.emplace_back(s, name);
  }
  std::sort(files.begin(), files.end());
  for (const auto& [s, name] : files) {
    h5::File f = h5::File::open_read_only(directory_ + "/" + name);
    XdmfEntry e;
    e.time = h5::read_attribute<double>(f, "/", "time");
    e.step = s;
    e.h5_file = name;
    e.particle_count = std::size_t(h5::read_attribute<std::int64_t>(f, "/", "particle_count"));
    e.fields = fields_;
    e.walls = read_wall_surface_info(f, "wall_surfaces");
    series_.push_back(e);
    const std::string mesh_file = meshes_h5_name(s);
    if (std::filesystem::exists(directory_ + "/" + mesh_file)) {
      h5::File m = h5::File::open_read_only(directory_ + "/" + mesh_file);
      mesh_series_.push_back({e.time, mesh_file, std::size_t(h5::dims_of(m, "/vertices")[0]),
                              std::size_t(h5::dims_of(m, "/triangles")[0])});
    }
  }
}

void RunOutput::checkpoint(const Simulation& sim) {
  // The state of the last snapshot (on every rank: the staging is collective):
  // its particles are the checkpoint's, the history is copied while that
  // snapshot's file, which does not read it, is still being written, and the
  // checkpoint's file follows it on the writer's thread (no wait here).
  const bool after_snapshot = transport_.min(staged_particles_are(sim) ? 1 : 0) == 1;
  // The previous files are complete before the host copy is refilled (after
  // a snapshot, only the history's, and only where a job still reads it).
  if (!after_snapshot || writing_history_) finish();
  const auto t = Clock::now();
  if (after_snapshot) stage_history(sim);
  else stage(sim, true, true);
  split_.host_copy += seconds_since(t);
  writing_history_ = true;
  if (transport_.rank() != 0) return;
  const std::optional<InsertionState> insertion =
      scene_.inlets.empty() ? std::nullopt : std::optional<InsertionState>(sim.insertion());
  // The header, walls and insertion state: none of them read by the snapshot's job.
  complete_checkpoint(staged_, sim.walls(), scene_hash_, transport_.size(), insertion);
  staged_.scene_text = scene_text_;
  auto job = [this] {
    const Checkpoint& c = staged_;  // refilled only after finish()
    const std::string path = directory_ + "/" + checkpoint_h5_name(c.step);
    const auto start = Clock::now();
    write_checkpoint(path, c);  // under a temporary name, renamed when complete
    const double seconds = seconds_since(start);
    // A file written again (a checkpoint of the same step) is the newest, once.
    checkpoints_.erase(std::remove(checkpoints_.begin(), checkpoints_.end(), path), checkpoints_.end());
    checkpoints_.push_back(path);
    while (checkpoints_.size() > 2) {
      std::filesystem::remove(checkpoints_.front());
      checkpoints_.erase(checkpoints_.begin());
    }
    log_written("checkpoint", path, seconds);
  };
  if (after_snapshot) writer_.then(job);
  else in_background(job);
}

void RunOutput::fault_snapshot(const Simulation& sim) {
  finish();
  const ParticleSnapshot s = gather_snapshot(transport_, sim.snapshot());
  const std::string path = directory_ + "/" + fault_snapshot_name(s.step);
  written_by_rank_0(transport_, [&] {
    SnapshotMetadata m;
    m.scene_hash = scene_hash_;
    m.scene_path = scene_.path;
    m.wall_names = scene_.wall_names;
    SnapshotFields fields = all_particle_fields();
    const unsigned kept = particle_fields_kept(scene_);  // the optional ones
    if (kept & kImageCounts) fields.add(SnapshotField::image);
    if (kept & kOrientations) fields.add(SnapshotField::orientation);
    if (keeps_history(scene_.model, scene_.effects)) {
      fields.add(SnapshotField::contact_count);
      m.contact_count = s.contacts;
    }
    write_snapshot(path, s, fields, sim.walls(), m);
  });
  log("state at the fault written to %s (step %lld)\n", path.c_str(), s.step);
}

}  // namespace gs
