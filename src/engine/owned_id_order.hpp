#pragma once
// The owned particles' store indices in ascending id order, for the kernels
// that put fields in id order (snapshots, checkpoints, the particles on
// walls). Ids are unique: where the owned ids span exactly as many values as
// there are particles (one rank's run without removals), particle k's place
// is its id less the smallest, a scatter that needs nothing beside the order.
// Elsewhere, on a GPU a radix sort of (id, index) pairs on the device, its
// keys and second buffers in the step's staging buffer as the cell list's
// sort has them (12 bytes per particle there, which a build frees again);
// on the CPU the host's linear-time order (core/id_order.hpp). Both give the
// one order.
#include <vector>

#include "backend/device_array.hpp"
#include "core/id_order.hpp"
#include "core/id_range.hpp"
#include "neighbor/cell_list.hpp"

namespace gs {

// keys[k] = id[k], values[k] = k.
struct IdKeys {
  const ParticleId* id;
  std::uint32_t* keys;
  Index* values;
  GS_HD void operator()(Index k) const {
    keys[k] = id[k];
    values[k] = k;
  }
};

// order[id[k] - lowest] = k.
struct PlaceById {
  const ParticleId* id;
  ParticleId lowest;
  Index* order;
  GS_HD void operator()(Index k) const { order[id[k] - lowest] = k; }
};

template <class Exec>
void owned_id_order(const ParticleId* id, Index n, DeviceArray<Index>& order, DeviceArray<unsigned char>& scratch) {
  order.resize_discarding(std::size_t(n));
  if (n == 0) return;
  const IdRange r = Exec::id_range(id, n, scratch);
  if (std::uint64_t(r.highest) - std::uint64_t(r.lowest) + 1 == std::uint64_t(n)) {
    Exec::parallel_for(n, PlaceById{id, r.lowest, order.data()});
    return;
  }
  if constexpr (Exec::backend == Backend::cpu) {
    const std::vector<std::size_t> o = id_order(std::vector<ParticleId>(id, id + n));
    Index* to = order.data();
    for (Index k = 0; k < n; ++k) to[k] = Index(o[std::size_t(k)]);
  } else {
    static_assert(sizeof(ParticleId) == sizeof(std::uint32_t), "ids are the sort's 32-bit keys");
    sort_in_scratch<Exec, std::uint32_t>(n, 32, order.data(), scratch, [&](SortPairs<std::uint32_t>& p) {
      Exec::parallel_for(n, IdKeys{id, p.keys, p.values});
    });
  }
}

}  // namespace gs
