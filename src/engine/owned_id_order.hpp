#pragma once
// The owned particles' store indices in ascending id order, for the kernels
// that put fields in id order (snapshots, checkpoints, the particles on
// walls). On a GPU a radix sort of (id, index) pairs on the device, its keys
// and second buffers in the step's staging buffer as the cell list's sort
// has them (so no more than the cell list's build needs); on the CPU the
// host's linear-time order (core/id_order.hpp). Ids are unique, so both give
// the one order.
#include <vector>

#include "backend/device_array.hpp"
#include "core/id_order.hpp"
#include "neighbor/cell_list.hpp"

namespace gs {

// keys[k] = id[k], values[k] = k.
struct IdKeys {
  const ParticleId* id;
  std::uint64_t* keys;
  Index* values;
  GS_HD void operator()(Index k) const {
    keys[k] = id[k];
    values[k] = k;
  }
};

template <class Exec>
void owned_id_order(const ParticleId* id, Index n, DeviceArray<Index>& order, DeviceArray<unsigned char>& scratch) {
  order.resize_discarding(std::size_t(n));
  if (n == 0) return;
  if constexpr (Exec::backend == Backend::cpu) {
    const std::vector<std::size_t> o = id_order(std::vector<ParticleId>(id, id + n));
    Index* to = order.data();
    for (Index k = 0; k < n; ++k) to[k] = Index(o[std::size_t(k)]);
  } else {
    constexpr int kKeyBits = 32;  // every id
    const std::size_t storage_bytes = Exec::sort_storage_bytes(n, kKeyBits);
    const SortLayout at(n, storage_bytes);
    scratch.resize_discarding(at.total);
    unsigned char* base = scratch.data();
    SortPairs p{reinterpret_cast<std::uint64_t*>(base + at.keys), reinterpret_cast<std::uint64_t*>(base + at.keys_alt),
                order.data(), reinterpret_cast<Index*>(base + at.values_alt), n, kKeyBits};
    Exec::parallel_for(n, IdKeys{id, p.keys, p.values});
    Exec::sort_pairs(p, base + at.storage, storage_bytes);
    if (p.values != order.data()) backend_copy(Exec::backend, order.data(), p.values, std::size_t(n) * sizeof(Index));
  }
}

}  // namespace gs
