#pragma once
// Every rank's owned particles in one snapshot on rank 0, sorted by id (for
// output: the files of a run do not depend on the number of ranks).
#include "comm/transport.hpp"
#include "engine/simulation.hpp"

namespace gs {

// Collective. Rank 0 gets the whole snapshot; other ranks an empty one.
// The parts are put in id order in linear time (core/id_order.hpp).
ParticleSnapshot gather_snapshot(Transport& transport, ParticleSnapshot local);
// The same into `all` (rank 0; other ranks: emptied), whose arrays keep
// their memory. With one rank, `all` may be `local` itself: nothing moves.
void gather_snapshot(Transport& transport, const ParticleSnapshot& local, ParticleSnapshot& all);
// Collective. The contact history of every particle on rank 0, in id order;
// `local` is in the order of `local_ids`.
HostHistory gather_history(Transport& transport, const std::vector<ParticleId>& local_ids, const HostHistory& local);
// The same into `all`, which may be `local` itself with one rank.
void gather_history(Transport& transport, const std::vector<ParticleId>& local_ids, const HostHistory& local,
                    HostHistory& all);
// Collective. Every rank's ids and history rows (local.id, local.history) on
// rank 0, sorted by id.
ParticleRecords gather_history_records(Transport& transport, const ParticleRecords& local);

}  // namespace gs
