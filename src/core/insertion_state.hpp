#pragma once
// Where the run's insertion stands: the run-wide next particle id and, per
// inlet, how far along its particle sequence it is. Checkpoints keep it, so a
// restart continues the same sequence with the same ids (engine/insertion.hpp).
#include <cstdint>
#include <vector>

namespace gs {

struct InletState {
  std::uint64_t inserted = 0;  // particles of the inlet's sequence inserted (the next one is this index)
  double mass = 0;             // their stored masses [kg], summed in sequence order
  std::uint64_t batches = 0;   // batches tried: counts the random draws of candidate positions
};

struct InsertionState {
  std::uint64_t next_id = 0;  // id of the next particle created during the run
  std::vector<InletState> inlets;  // per inlet of the scene, in scene order
};

// One inlet's batch, for the record of what was inserted (docs/OUTPUT.md, inlets.csv).
struct InsertionRecord {
  long long step = 0;
  double time = 0;
  int inlet = 0;
  std::uint64_t count = 0;     // inserted in this batch
  double mass = 0;             // their mass [kg]
  std::uint64_t shortfall = 0;  // due but not placed: carried to the next batch
  InletState total;            // after the batch
};

}  // namespace gs
