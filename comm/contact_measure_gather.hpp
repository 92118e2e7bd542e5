#pragma once
// The measurements' contact pass results of every rank on rank 0, in
// particle-id order (so they line up with gather_snapshot's snapshot).
#include <vector>

#include "comm/transport.hpp"
#include "core/contact_measure.hpp"
#include "core/types.hpp"

namespace gs {

// Collective. `local` belongs to `local_ids` (same order); rank 0 gets every
// rank's, sorted by id; other ranks an empty list.
std::vector<ContactMeasure> gather_contact_measures(Transport& transport, const std::vector<ParticleId>& local_ids,
                                                    const std::vector<ContactMeasure>& local);

}  // namespace gs
