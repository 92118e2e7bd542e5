#include "comm/rank_agreement.hpp"

#include <climits>
#include <vector>

namespace gs {

void throw_if_any_failed(Transport& transport, const std::string& local) {
  const bool failed = !local.empty();
  const int first = transport.min(failed ? transport.rank() : INT_MAX);
  if (first == INT_MAX) return;
  const Bytes text = transport.broadcast(Bytes(local.begin(), local.end()), first);
  const std::string message(text.begin(), text.end());
  // How many failed, and how many failed with the lowest failing rank's message.
  std::vector<std::int64_t> counts{failed ? 1 : 0, local == message ? 1 : 0};
  transport.sum(counts);
  if (counts[1] == transport.size()) throw RankFailure(message);
  std::string what = "rank " + std::to_string(first) + ": " + message;
  if (counts[0] > 1)
    what += " (and " + std::to_string(counts[0] - 1) + " more rank" + (counts[0] > 2 ? "s" : "") + " failed)";
  throw RankFailure(what);
}

}  // namespace gs
