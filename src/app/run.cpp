// `grainstorm run`: one rank, or one rank per GPU (or CPU) under mpirun. The
// run itself is the library's (run/driver.hpp); this parses the command line.
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/stop_signal.hpp"
#include "comm/rank_agreement.hpp"
#include "run/driver.hpp"

namespace gs {
namespace {

RunRequest parse_run_args(const std::vector<std::string>& args) {
  RunRequest r;
  std::set<std::string> seen;
  for (std::size_t k = 1; k < args.size(); ++k) {
    const std::string& a = args[k];
    // Given twice, one of the two would be dropped without a word.
    if (!a.empty() && a[0] == '-' && !seen.insert(a).second)
      throw std::invalid_argument("option " + a + " given twice");
    auto value = [&]() -> const std::string& {
      if (k + 1 >= args.size() || args[k + 1].empty()) throw std::invalid_argument("option " + a + " needs a value");
      return args[++k];
    };
    if (a == "--backend") r.backend = parse_backend(value());
    else if (a == "--steps")
      r.steps = whole_number(value(), 0, std::numeric_limits<long long>::max(),
                             "--steps must be a whole number >= 0 (the step to end at)");
    else if (a == "--out") r.out = value();
    else if (a == "--restart") r.restart = value();
    else if (a == "--overwrite") r.overwrite = true;
    else if (a == "--edited-scene") r.edited_scene = true;
    else if (a == "--exchange") r.exchange = value();
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else if (r.scene.empty()) r.scene = a;
    else throw std::invalid_argument("more than one scene given: " + a);
  }
  check_request(r);
  return r;
}

}  // namespace

int command_run(const std::vector<std::string>& args, Transport& transport) {
  // A bad command line on one rank ends every rank with the same error.
  RunRequest request;
  on_every_rank(transport, [&] { request = parse_run_args(args); });
  install_stop_signals();
  request.stop_requested = stop_requested;
  return run_scene(request, transport);
}

}  // namespace gs
