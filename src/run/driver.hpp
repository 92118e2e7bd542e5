#pragma once
// A whole run of a scene file, as `grainstorm run` does it: load and check the
// scene on every rank, split it over the ranks, start or restart the
// simulation, and step it with snapshots, checkpoints, the mixing analysis,
// marking, progress, the run log and stop requests in between. The command
// line (src/app/run.cpp) only parses its arguments into a RunRequest and
// installs the signal handlers; anything else that runs scenes (a benchmark,
// a test, a Python module) calls run_scene the same way.
#include <functional>
#include <memory>
#include <string>

#include "backend/backend.hpp"
#include "comm/transport.hpp"
#include "engine/simulation.hpp"
#include "scene/scene.hpp"

namespace gs {

struct RunRequest {
  std::string scene;  // the scene file
  Backend backend = default_backend();
  long long steps = -1;  // -1: the scene's duration
  std::string out;       // output directory; empty: the scene's output.directory
  std::string restart;   // a checkpoint to continue from; empty: a new run
  // The restart's scene may differ from the one that wrote the checkpoint
  // (run/edited_restart.hpp); without it a restart requires the same file.
  bool edited_scene = false;
  bool overwrite = false;  // replace an earlier run's files in the output directory
  // How GPU ranks move particles: "device" (NCCL), "host" (MPI through host
  // buffers), or "auto" (device when NCCL is built in and the backend is cuda).
  std::string exchange = "auto";
  // Polled after every step: true asks the run to write a checkpoint and
  // stop (the command line's SIGTERM and SIGUSR1). May be empty.
  std::function<bool()> stop_requested;
};

// std::invalid_argument naming the option when the request cannot be run
// (negative steps, an unknown exchange, a device exchange off the GPU,
// overwrite together with restart, an edited scene without a restart).
void check_request(const RunRequest& request);

// Collective over `transport`'s ranks. Returns the exit code: 0 when the run
// is complete, 3 when a stop request ended it after its checkpoint. Throws
// on bad input (every rank the same RankFailure), a SimulationFault (after
// logging it and writing the fault snapshot) or a failure to write.
int run_scene(const RunRequest& request, Transport& transport);

// How a run of a scene built in code starts (a benchmark, a test, a Python
// module): the simulation's options, and whether the packing checks run.
struct SceneStart {
  RunOptions options;
  // The packing checks of a loaded scene (scene/packing_check.hpp), spread
  // over the ranks; off for particles placed on purpose (a bed pressed into
  // overlap) or already checked.
  bool check_packing = true;
  std::string exchange = "auto";  // as RunRequest::exchange
};

// Collective over `transport`'s ranks: sets `scene` up as run_scene sets up a
// new run (the packing checks on the ranks, the split, each rank's own
// particles made once, the first forces) and hands back the simulation, to be
// stepped with Simulation::run. Throws on bad input (every rank the same
// RankFailure). `scene` keeps its particles; its kept fill blocks are let go.
std::unique_ptr<Simulation> start_scene(SceneSpec& scene, const SceneStart& start, Transport& transport);

// "1.5 MiB"
std::string human_bytes(double bytes);

// The scene's warnings (SceneSpec::warnings), one "warning: ..." line each on stderr.
void print_warnings(const SceneSpec& scene);

}  // namespace gs
