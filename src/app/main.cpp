// grainstorm command line: run and check scenes, describe output files.
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "backend/cpu/cpu_arch.hpp"
#include "comm/rank_agreement.hpp"
#include "comm/transport.hpp"
#include "engine/simulation.hpp"

namespace {

const char* kUsage =
    "grainstorm " GS_VERSION " - discrete element simulation of granular flows on GPUs and CPUs\n"
    "\n"
    "usage:\n"
    "  grainstorm run SCENE [--backend cpu|cuda] [--steps N] [--out DIR] [--overwrite | --restart CHECKPOINT.h5\n"
    "                 [--edited-scene]] [--exchange auto|device|host]\n"
    "      run a scene; by default on the GPU when one is present, for the scene's duration\n"
    "      (--steps N: to step N, counted from the run's start, also after a restart);\n"
    "      into --out (default: the scene's output.directory), which must be new or empty unless\n"
    "      --overwrite (first removes an earlier run's files from it) or --restart (continues the\n"
    "      checkpoint's run from its step, in this or another directory) is given; SIGTERM or\n"
    "      SIGUSR1 writes a checkpoint and exits with code 3 (under mpirun: docs/MULTI_RANK.md);\n"
    "      under mpirun/srun: one rank per GPU (or per CPU share with --backend cpu); GPU ranks\n"
    "      move particles over NCCL (device) when built with it and every rank has a GPU of its\n"
    "      own, else through the host;\n"
    "      --restart continues from a checkpoint the same scene file wrote, on any number of ranks;\n"
    "      with --edited-scene the scene may have been edited since (the run log lists the edits)\n"
    "  grainstorm check SCENE\n"
    "      validate a scene and print particle count, time step, contact time and memory estimate\n"
    "  grainstorm info FILE.h5\n"
    "      summarise an HDF5 snapshot or checkpoint: time, step, particles, fields, bounding box, scene hash;\n"
    "      exits with code 1 when the file is damaged (a checkpoint whose integrity check fails)\n"
    "  grainstorm mixing SCENE SNAPSHOT.h5... --out FILE.csv [--layers L]\n"
    "      the scene's mixing analysis (Lacey, RSD) over written snapshots, optionally with its\n"
    "      sample cylinders cut into L stacked samples; one CSV row per snapshot\n"
    "  grainstorm --help | -h | help | --version (or COMMAND --help: this text)\n"
    "\n"
    "The scene format is documented in docs/SCENES.md, output files in docs/OUTPUT.md.\n";

// Errors the ranks have agreed on (a phase one rank failed, a fault, bad
// input) are met by every rank together and reported once, by rank 0, and
// every rank exits 1. Any other error is one rank's alone, met in the middle
// of an exchange the others wait in: it is reported with the rank and every
// rank is stopped, so none waits forever.
int run_on_every_rank(const std::vector<std::string>& args) {
  std::unique_ptr<gs::Transport> transport;
  try {
    transport = gs::launched_by_mpi() ? gs::make_mpi_transport() : gs::make_single_transport();
    return gs::command_run(args, *transport);
  } catch (const gs::RankFailure& e) {
    if (transport->rank() == 0) std::fprintf(stderr, "grainstorm: error: %s\n", e.what());
    return 1;
  } catch (const gs::SimulationFault& e) {
    if (transport->rank() == 0) std::fprintf(stderr, "grainstorm: run stopped: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    if (!transport || transport->size() == 1) {
      std::fprintf(stderr, "grainstorm: error: %s\n", e.what());
      return 1;
    }
    std::fprintf(stderr, "grainstorm: rank %d: error: %s (stopping every rank)\n", transport->rank(), e.what());
    std::fflush(stderr);
    transport->abort(1);
    return 1;
  }
}

// `grainstorm --help` (or -h, help), or a command's (`grainstorm run
// SCENE --help`): the usage, not an error about a scene file called --help.
bool asks_for_help(const std::vector<std::string>& args) {
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") return true;
  for (std::size_t k = 1; k < args.size(); ++k)
    if (args[k] == "--help" || args[k] == "-h") return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || asks_for_help(args)) {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::printf("grainstorm %s (host code for %s)\n", GS_VERSION, gs::host_code_arch());
    return 0;
  }
  if (args[0] == "run") return run_on_every_rank(args);
  try {
    if (args[0] == "check") return gs::command_check(args);
    if (args[0] == "info") return gs::command_info(args);
    if (args[0] == "mixing") return gs::command_mixing(args);
    std::fprintf(stderr, "grainstorm: unknown command '%s'\n\n%s", args[0].c_str(), kUsage);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainstorm: error: %s\n", e.what());
    return 1;
  }
}
