#pragma once
// The output directory of a run: a new run goes into an empty (or new)
// directory, so that its files are never mixed with an earlier run's; a run
// continued from a checkpoint keeps the earlier run's files up to its step.
#include <string>

#include "scene/scene.hpp"

namespace gs {

enum class OutputDirectoryUse {
  fresh,      // must not exist or be empty
  overwrite,  // --overwrite: grainstorm's files from an earlier run are removed first
  restart,    // --restart: continues the run in it
};

// Throws std::runtime_error naming the directory when a fresh run would write
// into a non-empty one. Writes nothing.
void check_output_directory(const std::string& directory, OutputDirectoryUse use);

// Before the run writes: for `overwrite`, removes every file grainstorm
// writes (snapshots, meshes, checkpoints, fault snapshots, XDMF indexes,
// run.log, timeseries.csv, removed.csv, inlets.csv, the mixing log, the
// measurements' logs, grids and indexes, and leftover temporaries of them);
// for `restart` at `step`, removes the snapshots, meshes, fault snapshots and
// measurement grids after `step` and the rows after it from timeseries.csv,
// removed.csv, inlets.csv, the mixing log and the measurements' logs, which
// the continued run writes again. Other files are left alone.
void prepare_output_directory(const std::string& directory, OutputDirectoryUse use, const SceneSpec& scene,
                              long long step);

}  // namespace gs
