#pragma once
// Removal of the owned particles that reached an exit of the scene (an
// outlet region, or beyond an open face of the domain; scene/outlets.hpp).
// Data movement: the particles that stay keep their relative order and are
// compacted, with their forces and contact history, by the same kernel that
// compacts a rank's particles after migration (ParticleMovement::keep_owned),
// in the arrays they already have: no allocation once the step's buffers
// have grown. A partner's history slot that names a removed particle is
// freed at the next force computation, as for any contact that ended (ids are
// never reused, so it cannot be taken for another particle).
#include <cstdint>
#include <vector>

#include "engine/particle_store.hpp"
#include "scene/outlets.hpp"

namespace gs {

// One removed particle, for the removal log (run/removal_log.hpp).
struct RemovedParticle {
  long long step = 0;   // the step it was found in its exit
  ParticleId id = 0;
  float mass = 0;       // [kg], as the store keeps it
  std::int32_t exit = 0;  // index into Exits::names
  std::uint8_t material = 0, marker = 0;
};

constexpr std::int32_t kNoExit = -1;

// The exit that holds a particle centred at x: the first outlet (in scene
// order) that contains it, else the first open face (xmin to zmax) it is
// beyond, numbered as Exits::names; kNoExit when none does.
struct ExitOf {
  const OutletRegion* outlets;
  std::int32_t n_outlets;
  unsigned open_faces;
  Vec3d domain_lo, domain_hi;

  GS_HD std::int32_t operator()(const Vec3d& x) const {
    for (std::int32_t k = 0; k < n_outlets; ++k)
      if (outlet_contains(outlets[k], x)) return k;
    const unsigned beyond = faces_beyond(x, domain_lo, domain_hi) & open_faces;
    if (beyond == 0) return kNoExit;
    std::int32_t e = n_outlets;
    for (int f = 0; f < kDomainFaces; ++f) {
      const unsigned bit = 1u << f;
      if (beyond & bit) return e;
      if (open_faces & bit) ++e;
    }
    return kNoExit;
  }
};

// Tags each owned particle with its exit and counts the tagged ones (an
// integer count: the order of the increments does not matter).
struct TagExits {
  const Vec3d* position;
  ExitOf exit_of;
  std::int32_t* exit;
  unsigned* found;
  GS_HD void operator()(Index i) const {
    const std::int32_t e = exit_of(position[i]);
    exit[i] = e;
    if (e == kNoExit) return;
#if defined(__CUDA_ARCH__)
    atomicAdd(found, 1u);
#else
    __atomic_fetch_add(found, 1u, __ATOMIC_RELAXED);
#endif
  }
};

// Particles tagged with an exit (`leaving`) or with none.
struct ExitTagged {
  const std::int32_t* exit;
  bool leaving;
  GS_HD bool operator()(const Index& i) const { return (exit[i] != kNoExit) == leaving; }
};

class ParticleRemoval {
 public:
  virtual ~ParticleRemoval() = default;
  // The scene's exits and domain (once, before the first step).
  virtual void set_exits(const Exits& exits, const Vec3d& domain_lo, const Vec3d& domain_hi) = 0;
  // Removes the owned particles in an exit, found at `step`, and appends
  // them to `removed` in store order. When it removes any, the ghosts are
  // dropped too. Returns how many it removed.
  virtual Index remove(ParticleStore& s, long long step, std::vector<RemovedParticle>& removed) = 0;
  virtual std::size_t bytes() const = 0;
};

}  // namespace gs
