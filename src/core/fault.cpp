#include "core/fault.hpp"

namespace gs {

const char* fault_cause(int code) {
  switch (code) {
    case kFaultNone: return "no fault";
    case kFaultLeftDomain: return "the particle left the domain through a closed face (make the domain enclose "
                                  "everywhere particles can go, keep them in with a wall, or let them leave: "
                                  "domain.open or an outlet)";
    case kFaultTooFast: return "the particle moved more than half a cell in one step (time step too large or "
                               "unstable contact)";
    case kFaultNotFinite: return "position or velocity became NaN or Inf (numerical instability)";
    case kFaultSlotsExhausted: return "more simultaneous contacts than contact_slots (raise contact_slots)";
    case kFaultSurfaceSlotsExhausted: return "more simultaneous contacts with walls and mesh features than "
                                             "surface_slots (raise surface_slots)";
    case kFaultSurfaceUnforeseen: return "the particle touched a wall or mesh that the last build of the neighbour "
                                         "lists found out of its reach (a defect of grainstorm: please report it "
                                         "with the scene)";
    case kFaultListOutrun: return "the particle moved more than half the Verlet skin from where the list saw it in "
                                  "a step the list was kept for: its move grew by more than the list's margin (a "
                                  "tenth of the skin) in one step (time step too large or unstable contact)";
    default: return "unknown fault";
  }
}

}  // namespace gs
