#pragma once
// What a run writes beside itself: snapshots (HDF5 with an XDMF index, or
// CSV), checkpoints, a time series of scalars and a log. Collective: every
// rank calls each member; rank 0 writes, and a failure to write (a full disk)
// stops every rank with the same RankFailure (comm/rank_agreement.hpp).
// Snapshot and checkpoint files are written on a thread of their own
// (io/background_writer.hpp) while the run steps on: the next snapshot,
// checkpoint or finish() waits for them and reports their failure. Their host
// copies are one set of arrays kept from output to output (a GPU writes them
// through a pinned bounce buffer, backend/host_pins.hpp); the writer reads
// them, and they are refilled only after that wait. A checkpoint of the
// state the last snapshot copied (the same Simulation object at the same
// step: the caller changes nothing between the two) takes that
// snapshot's particles as they are, where that copy holds the forces (the
// snapshot was told a checkpoint follows, or its fields name them), copies
// the contact history, which the snapshot's file does not read, while that
// file is still being written, and hands its file to the writer to follow
// the snapshot's, without a wait.
#include <cstdio>
#include <string>
#include <vector>

#include <functional>
#include <memory>
#include <mutex>

#include "analysis/mixing_log.hpp"
#include "comm/transport.hpp"
#include "engine/simulation.hpp"
#include "io/checkpoint.hpp"
#include "io/h5_meshes.hpp"
#include "io/snapshot_fields.hpp"
#include "io/xdmf_series.hpp"
#include "io/background_writer.hpp"
#include "run/removal_log.hpp"

namespace gs {

class RunOutput {
 public:
  // `scene_text`: the scene file's text, stored in checkpoints (its hash in every file).
  RunOutput(const SceneSpec& scene, const std::string& directory, Transport& transport, std::string scene_text);
  ~RunOutput();
  RunOutput(const RunOutput&) = delete;
  RunOutput& operator=(const RunOutput&) = delete;

  // A snapshot and a time-series row. Its host copy holds the forces and
  // torques only where the snapshot's fields name them or, with
  // `checkpoint_follows`, where a checkpoint of this state is next (which
  // then takes the copy as it is): no time-series value reads them.
  void snapshot(const Simulation& sim, bool checkpoint_follows = false);
  void checkpoint(const Simulation& sim);  // keeps the newest two
  // Waits until every snapshot and checkpoint handed over is complete on
  // disk; a failure to write one stops every rank (RankFailure).
  void finish();
  void mixing(const Simulation& sim);      // one row of the mixing analysis (scene.mixing)
  // The particles every rank removed at the scene's exits since the last
  // call, as rows of removed.csv (nothing when the scene has no exits).
  void removals(Simulation& sim);
  // After a fault: every particle field of the state the fault was found in,
  // as fault_<step>.h5 (an HDF5 snapshot whatever the output format).
  void fault_snapshot(const Simulation& sim);
  // After a restart at `step`: the XDMF indexes keep the snapshots written
  // before it (read back from the files in the output directory).
  void resume(long long step);
  // printf to stdout and the log file, rank 0 only.
  void log(const char* format, ...) __attribute__((format(printf, 2, 3)));
  // Where the output's time went on this rank so far (wall seconds): waiting
  // for the writer's thread (finish(), inside each snapshot and checkpoint and
  // at the end), the host copies of particles and history with their gathers
  // to rank 0, the particles on walls, the mesh loads and the time-series row.
  struct Split {
    double waiting = 0, host_copy = 0, wall_records = 0, mesh_loads = 0, series = 0;
  };
  const Split& split() const { return split_; }
  const std::string& directory() const { return directory_; }

 private:
  void in_background(std::function<void()> job);
  void log_written(const char* what, const std::string& path, double seconds);  // a file's size and speed  // rank 0 starts it on writer_ (after finish())
  void index_earlier_snapshots(long long step);  // rank 0's part of resume()
  // Rank 0's parts of snapshot(): the time-series row, and the snapshot
  // files (on the writer's thread).
  void write_timeseries_row(const Simulation& sim, const ParticleSnapshot& s, const ParticleRecords& on_walls,
                            const std::vector<double>& mesh_load);
  void write_snapshot_files(const ParticleSnapshot& s, const std::vector<Wall>& walls, const MeshSet& meshes);
  void stage(const Simulation& sim, bool with_history, bool with_forces);  // the host copy in staged_ (rank 0)
  void stage_history(const Simulation& sim);             // staged_'s history alone
  // Whether staged_'s particles hold the state of `sim` now, and all of it (the forces too).
  bool staged_particles_are(const Simulation& sim) const;

  const SceneSpec& scene_;
  std::string directory_;
  Transport& transport_;
  std::string scene_text_;
  std::uint64_t scene_hash_;
  SnapshotFields fields_;
  std::vector<XdmfEntry> series_;
  std::vector<MeshSeriesEntry> mesh_series_;
  std::vector<std::string> checkpoints_;
  std::FILE* log_ = nullptr;
  std::FILE* timeseries_ = nullptr;
  std::unique_ptr<MixingLog> mixing_log_;
  std::unique_ptr<RemovalLog> removal_log_;
  std::mutex log_mutex_;
  // The host copy of the last snapshot or checkpoint: every particle on rank
  // 0, read by the writer's job; with several ranks each rank's own first.
  Checkpoint staged_;
  ParticleSnapshot local_;
  HostHistory local_history_;
  ParticleRecords on_walls_;  // this rank's particles on a wall, at the last snapshot
  // Whose state the particles in staged_ (and local_) hold: a simulation at a step.
  struct StagedState {
    const Simulation* sim = nullptr;
    long long step = -1;
    Index owned = -1;
    bool forces = false;  // the forces and torques were copied too
  } staged_from_;
  bool writing_history_ = false;  // the writer's job in hand reads staged_.history
  Split split_;
  HostPins pins_;  // resizes the arrays; the pinned bounce buffer of a GPU's copies
  // Last: destroyed first, so its job ends while the members it uses live.
  BackgroundWriter writer_;
};

}  // namespace gs
