#pragma once
// Agreement on errors between ranks. A phase of a run that one rank can fail
// alone (a file it cannot open, memory it cannot get) ends with every rank
// learning whether any failed, so no rank goes on into a collective the
// others never reach: all of them stop together with the same message.
#include <stdexcept>
#include <string>

#include "comm/transport.hpp"

namespace gs {

// Thrown on every rank by throw_if_any_failed: the same message everywhere.
struct RankFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Collective. `local` is this rank's error ("" for none). When no rank
// failed it returns; otherwise every rank throws RankFailure with the error
// of the lowest failing rank, as "rank R: message", followed by how many other
// ranks failed. When every rank failed with the same message (bad input read
// alike everywhere, or a single rank) the message stands alone.
void throw_if_any_failed(Transport& transport, const std::string& local);

}  // namespace gs
