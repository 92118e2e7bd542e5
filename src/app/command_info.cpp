// grainstorm info FILE.h5: what a snapshot or checkpoint holds.
#include <cstdio>
#include <stdexcept>

#include "app/commands.hpp"
#include "io/h5_describe.hpp"

namespace gs {

int command_info(const std::vector<std::string>& args) {
  if (args.size() != 2) throw std::invalid_argument("usage: grainstorm info FILE.h5");
  std::fputs(describe_h5(args[1]).c_str(), stdout);
  return 0;
}

}  // namespace gs
