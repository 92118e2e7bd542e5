#pragma once
// A fault found inside a kernel: the first one wins and is reported by the
// host with the step and particle id, then the run stops.
#include "core/hd.hpp"
#include "core/types.hpp"

namespace gs {

enum FaultCode : int {
  kFaultNone = 0,
  kFaultLeftDomain = 1,       // a particle left the simulation domain
  kFaultTooFast = 2,          // a particle moved more than half a cell in one step
  kFaultNotFinite = 3,        // NaN or Inf in position or velocity
  kFaultSlotsExhausted = 4,   // more simultaneous contacts than contact_slots
  kFaultListOutrun = 5,       // moved past a Verlet list kept on a verdict read a step late (neighbor/verlet_list.hpp)
  kFaultSurfaceSlotsExhausted = 6,  // more simultaneous wall and mesh contacts than surface_slots
  kFaultSurfaceUnforeseen = 7,  // a wall or mesh contact of a particle the last build gave no slots (a defect)
};

struct Fault {
  int code;
  ParticleId particle;
  long long step;
};

const char* fault_cause(int code);

GS_HD GS_INLINE void report_fault(Fault* f, int code, ParticleId particle, long long step) {
#if defined(__CUDA_ARCH__)
  if (atomicCAS(&f->code, 0, code) == 0) {
    f->particle = particle;
    f->step = step;
  }
#else
  int expected = 0;
  if (__atomic_compare_exchange_n(&f->code, &expected, code, false, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
    f->particle = particle;
    f->step = step;
  }
#endif
}

}  // namespace gs
