#pragma once
// What a run split over several ranks needs from comm/: ownership, migration,
// ghosts, load balance and agreement on faults. The engine sees only this
// interface, so it depends on no transport (comm/ implements it over MPI).
#include <string>

#include "engine/particle_store.hpp"
#include "engine/particle_movement.hpp"

namespace gs {

// Where the exchange's time goes, summed over the timed steps only (see
// Simulation::phase_seconds): deciding who goes where, packing messages,
// moving them (which includes waiting for slower peers), and unpacking
// arrivals and compacting the owned particles. Forwarding between rebuilds
// counts as pack, transfer and unpack; deciding whether to rebuild as route.
// The counts cover every step, timed or not.
struct ExchangeSplit {
  double route = 0, pack = 0, transfer = 0, unpack = 0;
  long long rebuilds = 0;  // steps that migrated and selected the ghosts anew
  long long forwards = 0;  // steps that only forwarded the ghosts' changing fields
  double total() const { return route + pack + transfer + unpack; }
};

class RankExchange {
 public:
  virtual ~RankExchange() = default;

  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  virtual bool owns(const Vec3d& x) const = 0;
  // A box holding every point of the domain this rank owns.
  virtual void owned_bounds(Vec3d& lo, Vec3d& hi) const = 0;

  // Owned particles that left this rank's region go, with their contact
  // history, to their new owners; arrivals are appended. Drops the ghosts.
  virtual void migrate(ParticleStore& s, ParticleMovement& k) = 0;
  // Replaces the ghosts with copies of the neighbours' particles that lie
  // within the halo (interaction range plus skin) of this rank's region, and
  // records who sent what (the send lists, where each peer's ghosts lie),
  // for forward_ghosts.
  virtual void refresh_ghosts(ParticleStore& s, ParticleMovement& k) = 0;
  // The skin [m] the halo adds to the interaction range; returns the skin it
  // will use: less where the decomposition's coarse cells are narrower than
  // range plus skin (its neighbours then hold only ranks within the cells).
  virtual double set_skin(double skin) = 0;
  // Collective: whether the halo must be rebuilt now (migrate or rebalance,
  // then refresh_ghosts): on some rank `due` holds (among its reasons, the
  // kick-drift's verdict that an owned particle may have moved half the skin
  // since the rebuild: Simulation::exchange_particles) or its store changed
  // since the last refresh_ghosts (ParticleStore::revision: removal,
  // insertion). Until then every contact partner of an owned particle is a
  // ghost already (docs/MULTI_RANK.md).
  virtual bool halo_stale(const ParticleStore& s, ParticleMovement& k, bool due) = 0;
  // Between rebuilds: each ghost gets its owner's changing fields
  // (engine/ghost_forward.hpp) over the send lists of the last refresh_ghosts,
  // in two halves, so that what needs no ghost can be computed while the
  // messages travel: start_forward packs and sends them, finish_forward
  // receives and unpacks them (the ghosts hold the new fields only then).
  // Collective, each half; nothing else may use the exchange between them.
  // Owned particles stay on this rank, even those that left its region.
  virtual void start_forward(ParticleStore& s, ParticleMovement& k) = 0;
  virtual void finish_forward(ParticleStore& s, ParticleMovement& k) = 0;
  // Collective. Re-partitions when the load imbalance (max / mean particles
  // per rank) exceeds the scene's threshold, and migrates; true if it did.
  virtual bool rebalance(ParticleStore& s, ParticleMovement& k) = 0;
  // Collective: the fault of the lowest failing rank, as "rank R: message",
  // or "" when no rank failed.
  virtual std::string first_fault(const std::string& local) = 0;
  // Collective: particles on all ranks.
  virtual long long total(long long local) = 0;
  // Collective: element-wise sum over ranks, in place (e.g. mesh loads). Not
  // bitwise independent of the rank count.
  virtual void sum(std::vector<double>& values) = 0;

  virtual std::string describe() const = 0;  // partition and imbalance, for the log
  // Times the following migrate / refresh_ghosts calls phase by phase, waiting
  // for the device between phases, or stops doing so.
  virtual void time_phases(bool on) = 0;
  virtual ExchangeSplit split() const = 0;
};

}  // namespace gs
