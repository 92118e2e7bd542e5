#pragma once
// The insertion state in a checkpoint (docs/OUTPUT.md): group `insertion`,
// present only for a run with inlets, so a checkpoint of any other run is
// unchanged.
#include <optional>

#include "core/insertion_state.hpp"
#include "io/fnv1a.hpp"
#include "io/h5_io.hpp"

namespace gs {

void write_insertion(const h5::File& f, const InsertionState& s);
std::optional<InsertionState> read_insertion(const h5::File& f);  // none without the group
void add_insertion(Fnv1a64& sum, const InsertionState& s);        // to the checkpoint's checksum

}  // namespace gs
