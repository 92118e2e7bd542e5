#pragma once
// What a run writes beside itself: snapshots (HDF5 with an XDMF index, or
// CSV), checkpoints, a time series of scalars and a log. Collective: every
// rank calls each member; rank 0 writes.
#include <cstdio>
#include <string>
#include <vector>

#include <memory>

#include "analysis/mixing_log.hpp"
#include "comm/transport.hpp"
#include "engine/simulation.hpp"
#include "io/h5_meshes.hpp"
#include "io/snapshot_fields.hpp"
#include "io/xdmf_series.hpp"

namespace gs {

class RunOutput {
 public:
  RunOutput(const SceneSpec& scene, const std::string& directory, Transport& transport, std::uint64_t scene_hash);
  ~RunOutput();
  RunOutput(const RunOutput&) = delete;
  RunOutput& operator=(const RunOutput&) = delete;

  void snapshot(const Simulation& sim);    // and a time-series row
  void checkpoint(const Simulation& sim);  // keeps the newest two
  void mixing(const Simulation& sim);      // one row of the mixing analysis (scene.mixing)
  // After a restart at `step`: the XDMF indexes keep the snapshots written
  // before it (read back from the files in the output directory).
  void resume(long long step);
  // printf to stdout and the log file, rank 0 only.
  void log(const char* format, ...) __attribute__((format(printf, 2, 3)));

 private:
  const SceneSpec& scene_;
  std::string directory_;
  Transport& transport_;
  std::uint64_t scene_hash_;
  SnapshotFields fields_;
  std::vector<XdmfEntry> series_;
  std::vector<MeshSeriesEntry> mesh_series_;
  std::vector<std::string> checkpoints_;
  std::FILE* log_ = nullptr;
  std::FILE* timeseries_ = nullptr;
  std::unique_ptr<MixingLog> mixing_log_;
};

}  // namespace gs
