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

// Collective. Runs `phase`, which must not communicate, on this rank; then
// throw_if_any_failed with the error it threw ("unknown error" where its
// message is empty, which would otherwise read as no error), so that a
// phase failing on some ranks stops all of them together.
template <class Phase>
void on_every_rank(Transport& transport, Phase&& phase) {
  std::string error;
  try {
    phase();
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unknown error";
  }
  throw_if_any_failed(transport, error);
}

// Collective. Rank 0 alone runs `write` (a file only it writes; it must not
// communicate); then every rank learns whether it could, so that a failed
// write stops all of them at the same point instead of leaving the others
// in the next collective.
template <class Write>
void written_by_rank_0(Transport& transport, Write&& write) {
  on_every_rank(transport, [&] {
    if (transport.rank() == 0) write();
  });
}

}  // namespace gs
