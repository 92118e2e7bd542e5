#pragma once
// HDF5 particle snapshots (docs/OUTPUT.md): one file per output time with the
// particle fields the scene selected, the walls, and the time, step and scene
// they belong to. Written to a temporary file and renamed, so a snapshot file
// that exists is complete.
#include <cstdint>
#include <string>
#include <vector>

#include "core/particle_snapshot.hpp"
#include <optional>

#include "io/snapshot_fields.hpp"
#include "io/wall_surfaces.hpp"
#include "walls/wall.hpp"

namespace gs {

constexpr int kSnapshotFormatVersion = 1;

struct SnapshotMetadata {
  std::uint64_t scene_hash = 0;              // scene_hash() of the scene file's text
  std::string scene_path;                    // the scene file, for the reader's information
  std::vector<std::string> wall_names;       // empty, or one name per wall
  std::vector<std::uint16_t> contact_count;  // contacts per particle in snapshot order;
                                             // required when the fields select contact_count
  std::optional<DomainBox> domain;           // when set, the walls' surfaces are written too
                                             // (group wall_surfaces), planes clipped to it
};

// particles_<step, 10 digits>.h5
std::string snapshot_h5_name(long long step);

// Writes `s` (its time and step too) with the selected fields and `walls` at
// their current pose. Throws std::invalid_argument when a selected field does
// not hold one value per particle, and h5::H5Error when HDF5 fails.
void write_snapshot(const std::string& path, const ParticleSnapshot& s, const SnapshotFields& fields,
                    const std::vector<Wall>& walls, const SnapshotMetadata& metadata);

// Reads back a snapshot's time, step and whichever of id, material, marker,
// radius, mass, position and velocity it holds (the others stay empty).
// h5::FormatError when the file is not a grainstorm snapshot or a field has
// the wrong shape or type.
ParticleSnapshot read_snapshot(const std::string& path);
// The wall surfaces a snapshot holds (empty when it was written without a domain).
std::vector<WallSurfaceInfo> read_snapshot_wall_surfaces(const std::string& path);

}  // namespace gs
