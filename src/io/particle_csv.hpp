#pragma once
// Plain-text particle snapshots (docs/OUTPUT.md): one CSV file per output
// time, written to a temporary name and renamed, so a file that exists is
// complete.
#include <string>

#include "core/particle_snapshot.hpp"

namespace gs {

void write_particles_csv(const std::string& path, const ParticleSnapshot& s);
std::string snapshot_file_name(long long step);  // particles_<step, 10 digits>.csv

}  // namespace gs
