#pragma once
// Velocity Verlet over the owned particles (integrate/velocity_verlet.hpp),
// split around the force computation: a half kick and a drift before it, a
// half kick after it.
#include "engine/particle_store.hpp"
#include "integrate/velocity_verlet.hpp"

namespace gs {

class Integration {
 public:
  virtual ~Integration() = default;
  // closing_kick: the last step's closing half kick was deferred to this
  // pass (KickDrift::closing_kick).
  virtual void kick_drift(ParticleStore& s, const IntegrationParams& p, bool closing_kick) = 0;
  virtual void kick(ParticleStore& s, const IntegrationParams& p) = 0;
};

}  // namespace gs
