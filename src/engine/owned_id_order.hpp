#pragma once
// The owned particles' order by ascending id, for the kernels that put
// fields in id order (snapshots, checkpoints). Ids are unique: where the
// owned ids span exactly as many values as there are particles (one rank's
// run without removals), particle k's place is its id less the smallest,
// and the order is that scatter (engine/row_order.hpp): nothing is held
// beside the run. Elsewhere the store indices in id order, an order array:
// on a GPU a radix sort of (id, index) pairs on the device, its keys and
// second buffers in the step's staging buffer as the cell list's sort has
// them (12 bytes per particle there, which a build frees again); on the CPU
// the host's linear-time order (core/id_order.hpp). Both give the one order.
#include <vector>

#include "backend/device_array.hpp"
#include "core/id_order.hpp"
#include "core/id_range.hpp"
#include "engine/row_order.hpp"
#include "neighbor/cell_list.hpp"

namespace gs {

// keys[k] = id[i], values[k] = i for store index i = at[k] (at null: k).
struct IdKeys {
  const ParticleId* id;
  const Index* at;
  std::uint32_t* keys;
  Index* values;
  GS_HD void operator()(Index k) const {
    const Index i = at ? at[k] : k;
    keys[k] = id[i];
    values[k] = i;
  }
};

// Store indices at[0, m) (at null: 0 to m - 1) into `out` by ascending id:
// a radix sort of their (id, index) pairs on the backend, its keys and
// second buffers in `scratch`.
template <class Exec>
void sort_by_id(const ParticleId* id, const Index* at, Index m, Index* out, DeviceArray<unsigned char>& scratch) {
  static_assert(sizeof(ParticleId) == sizeof(std::uint32_t), "ids are the sort's 32-bit keys");
  if (m == 0) return;
  sort_in_scratch<Exec, std::uint32_t>(m, 32, out, scratch, [&](SortPairs<std::uint32_t>& p) {
    Exec::parallel_for(m, IdKeys{id, at, p.keys, p.values});
  });
}

// The owned order as a RowOrder: the scatter by id where the ids are dense,
// else a gather over `storage` (an empty array, filled here; left empty
// for the scatter).
template <class Exec>
RowOrder owned_row_order(const ParticleId* id, Index n, DeviceArray<Index>& storage,
                         DeviceArray<unsigned char>& scratch) {
  if (n == 0) return RowOrder{};
  const IdRange r = Exec::id_range(id, n, scratch);
  if (std::uint64_t(r.highest) - std::uint64_t(r.lowest) + 1 == std::uint64_t(n))
    return RowOrder::scatter(id, r.lowest, n);
  storage.resize_discarding(std::size_t(n));
  if constexpr (Exec::backend == Backend::cpu) {
    const std::vector<std::size_t> o = id_order(std::vector<ParticleId>(id, id + n));
    Index* to = storage.data();
    for (Index k = 0; k < n; ++k) to[k] = Index(o[std::size_t(k)]);
  } else {
    sort_by_id<Exec>(id, nullptr, n, storage.data(), scratch);
  }
  return RowOrder::gather(storage.data());
}

}  // namespace gs
