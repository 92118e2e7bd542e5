#pragma once
// Where each row of an output in id order comes from (snapshots,
// checkpoints, messages): row r from store index order[r], a gather over an
// order array; or, where the owned ids are dense (they span exactly as many
// values as there are particles: one rank's run without removals), from the
// store index whose id less the smallest is r, a scatter that needs no order
// array: any window of rows is found by one pass over the n store indices,
// each writing its row where it falls inside the window. Neither: store
// order. engine/owned_id_order.hpp makes the order of the owned particles.
#include "core/hd.hpp"
#include "core/types.hpp"

namespace gs {

struct RowOrder {
  const Index* order = nullptr;    // a gather (null: store order, or a scatter by id)
  const ParticleId* id = nullptr;  // with order null: a scatter by id - lowest
  ParticleId lowest = 0;
  Index n = 0;  // the store indices a scatter passes over

  static RowOrder gather(const Index* order) { return RowOrder{order, nullptr, 0, 0}; }
  static RowOrder scatter(const ParticleId* id, ParticleId lowest, Index n) { return RowOrder{nullptr, id, lowest, n}; }
  bool scatters() const { return order == nullptr && id != nullptr; }
};

// body(k, i): row k of the window from store index i.
template <class Body>
struct RowsGathered {
  const Index* order;
  Index first;
  Body body;
  GS_HD void operator()(Index k) const { body(k, order ? order[first + k] : first + k); }
};

// Store index i puts its row where its id falls inside the m rows from id
// `from` (below `from` the unsigned difference wraps above m).
template <class Body>
struct RowsScattered {
  const ParticleId* id;
  ParticleId from;
  Index m;
  Body body;
  GS_HD void operator()(Index i) const {
    const ParticleId k = id[i] - from;
    if (k < ParticleId(m)) body(Index(k), i);
  }
};

// body(k, i) for the rows k of the window [first, first + m) of the order
// (k counted from first), i each row's store index: every row once.
template <class Exec, class Body>
void for_rows(const RowOrder& o, Index first, Index m, const Body& body) {
  if (m <= 0) return;
  if (o.scatters())
    Exec::parallel_for(o.n, RowsScattered<Body>{o.id, o.lowest + ParticleId(first), m, body});
  else
    Exec::parallel_for(m, RowsGathered<Body>{o.order, first, body});
}

}  // namespace gs
