// grainstorm info FILE.h5: what a snapshot or checkpoint holds.
#include <cstdio>
#include <stdexcept>

#include "app/commands.hpp"
#include "io/h5_describe.hpp"

namespace gs {

int command_info(const std::vector<std::string>& args) {
  if (args.size() != 2) throw std::invalid_argument("usage: grainstorm info FILE.h5");
  const H5Description d = describe_h5(args[1]);
  std::fputs(d.text.c_str(), stdout);
  if (!d.damaged) return 0;
  // A script that checks a checkpoint before restarting from it reads the exit code.
  std::fprintf(stderr, "grainstorm: error: %s is damaged (see its integrity line)\n", args[1].c_str());
  return 1;
}

}  // namespace gs
