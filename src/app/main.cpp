// grainstorm command line: run and check scenes.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/commands.hpp"

namespace {

const char* kUsage =
    "grainstorm " GS_VERSION " - discrete element simulation of granular flows on GPUs and CPUs\n"
    "\n"
    "usage:\n"
    "  grainstorm run SCENE [--backend cpu|cuda] [--steps N] [--out DIR]\n"
    "      run a scene; by default on the GPU when one is present, for the scene's duration\n"
    "  grainstorm check SCENE\n"
    "      validate a scene and print particle count, time step, contact time and memory estimate\n"
    "  grainstorm --help | --version\n"
    "\n"
    "The scene format is documented in docs/SCENES.md.\n";

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::printf("grainstorm %s\n", GS_VERSION);
    return 0;
  }
  try {
    if (args[0] == "run") return gs::command_run(args);
    if (args[0] == "check") return gs::command_check(args);
    std::fprintf(stderr, "grainstorm: unknown command '%s'\n\n%s", args[0].c_str(), kUsage);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainstorm: error: %s\n", e.what());
    return 1;
  }
}
