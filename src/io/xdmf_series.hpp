#pragma once
// An XDMF 3 index over a run's HDF5 snapshots (docs/OUTPUT.md): a temporal
// collection of point clouds (Polyvertex topology, XYZ geometry from
// /particles/position, one attribute per other field), so ParaView or VisIt
// open the whole run as one time series; a second temporal collection holds
// the analytic walls' surfaces (one triangle grid per wall) where the
// snapshots have them. The .xdmf file holds no data, only references into the
// .h5 files, and is rewritten after every snapshot.
#include <cstddef>
#include <string>
#include <vector>

#include "core/particle_snapshot.hpp"
#include "io/snapshot_fields.hpp"
#include "io/wall_surfaces.hpp"

namespace gs {

struct XdmfEntry {
  double time = 0;
  long long step = 0;
  std::string h5_file;  // as the index refers to it: relative to the .xdmf file's directory
  std::size_t particle_count = 0;
  SnapshotFields fields;
  std::vector<WallSurfaceInfo> walls;  // the snapshot's wall surfaces (group wall_surfaces), if any
};

XdmfEntry xdmf_entry(const std::string& h5_file, const ParticleSnapshot& s, const SnapshotFields& fields,
                     std::vector<WallSurfaceInfo> walls = {});

// The XDMF document over `entries`, in the given (time) order.
std::string xdmf_series_text(const std::vector<XdmfEntry>& entries);
// Writes it to `path` atomically.
void write_xdmf_series(const std::string& path, const std::vector<XdmfEntry>& entries);

}  // namespace gs
