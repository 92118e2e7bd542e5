#pragma once
#include "core/types.hpp"

namespace gs {

// The smallest and the largest of a set of particle ids (Exec::id_range).
struct IdRange {
  ParticleId lowest = 0, highest = 0;
};

}  // namespace gs
