#include "core/fault.hpp"

namespace gs {

const char* fault_cause(int code) {
  switch (code) {
    case kFaultNone: return "no fault";
    case kFaultLeftDomain: return "the particle left the domain";
    case kFaultTooFast: return "the particle moved more than half a cell in one step (time step too large or "
                               "unstable contact)";
    case kFaultNotFinite: return "position or velocity became NaN or Inf (numerical instability)";
    case kFaultSlotsExhausted: return "more simultaneous contacts than contact_slots (raise contact_slots)";
    case kFaultListMargin: return "the particle's acceleration changed its move in one step by more than the Verlet "
                                  "list's margin (|a| dt^2 above 0.09 of the skin: time step too large or unstable "
                                  "contact)";
    default: return "unknown fault";
  }
}

}  // namespace gs
