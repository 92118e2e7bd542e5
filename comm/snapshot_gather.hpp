#pragma once
// Every rank's owned particles in one snapshot on rank 0, sorted by id (for
// output: the files of a run do not depend on the number of ranks).
#include "comm/transport.hpp"
#include "engine/simulation.hpp"

namespace gs {

// Collective. Rank 0 gets the whole snapshot; other ranks an empty one.
// The parts are put in id order in linear time (core/id_order.hpp).
ParticleSnapshot gather_snapshot(Transport& transport, ParticleSnapshot local);
// Collective. The contact history of every particle on rank 0, in id order;
// `local` is in the order of `local_ids`.
HostHistory gather_history(Transport& transport, const std::vector<ParticleId>& local_ids, const HostHistory& local);
// Collective. Every rank's ids and history rows (local.id, local.history) on
// rank 0, sorted by id.
ParticleRecords gather_history_records(Transport& transport, const ParticleRecords& local);

}  // namespace gs
