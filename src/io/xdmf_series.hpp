#pragma once
// An XDMF 3 index over a run's HDF5 snapshots (docs/OUTPUT.md): a temporal
// collection of point clouds (Polyvertex topology, XYZ geometry from
// /particles/position, one attribute per other field), so ParaView or VisIt
// open the whole run as one time series. The .xmf file holds no data, only
// references into the .h5 files, and is rewritten after every snapshot.
#include <cstddef>
#include <string>
#include <vector>

#include "engine/simulation.hpp"
#include "io/snapshot_fields.hpp"

namespace gs {

struct XdmfEntry {
  double time = 0;
  long long step = 0;
  std::string h5_file;  // as the .xmf refers to it: relative to the .xmf file's directory
  std::size_t particle_count = 0;
  SnapshotFields fields;
};

XdmfEntry xdmf_entry(const std::string& h5_file, const ParticleSnapshot& s, const SnapshotFields& fields);

// The XDMF document over `entries`, in the given (time) order.
std::string xdmf_series_text(const std::vector<XdmfEntry>& entries);
// Writes it to `path` atomically.
void write_xdmf_series(const std::string& path, const std::vector<XdmfEntry>& entries);

}  // namespace gs
