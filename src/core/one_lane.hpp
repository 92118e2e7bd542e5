#pragma once
// A group of one lane (a host thread, or a GPU thread alone): the lane
// group's interface (backend/cuda/lane_group.cuh) where nothing is shared, so
// that one body serves a kernel run by a thread per particle and one run by a
// group of lanes per particle (in_group).
#include "core/hd.hpp"

namespace gs {

struct OneLane {
  static constexpr int size = 1;
  static constexpr int rank = 0;
  GS_HD static bool leader() { return true; }
  GS_HD static unsigned ballot(bool vote) { return vote ? 1u : 0u; }
  GS_HD static void sync() {}  // nothing to wait for: this lane wrote it all
};

}  // namespace gs
