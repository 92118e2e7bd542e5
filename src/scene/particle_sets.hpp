#pragma once
// The scene's particles as sets: one particle, the properties a generated set
// shares, and a lattice kept as its description.
#include <cstddef>
#include <cstdint>

#include "core/types.hpp"
#include "core/vec3.hpp"

namespace gs {

// One particle as created at t = 0.
struct ParticleInit {
  ParticleId id = 0;
  int material = 0;
  double radius = 0;
  Vec3d position, velocity, angular_velocity;
  std::uint8_t marker = 0;
  std::uint8_t frozen = 0;  // 1: never moves, still touches (docs/SCENES.md, `frozen`)
};

// Properties shared by every particle of one generated set.
struct ParticleTemplate {
  int material = 0;
  Vec3d velocity;
  Vec3d angular_velocity;
  std::uint8_t marker = 0;
  bool frozen = false;
};

// Simple cubic lattice: centres min + spacing * (i, j, k) that lie inside [min, max].
struct LatticeSpec {
  ParticleTemplate tmpl;
  double radius = 0;
  Vec3d min, max;
  double spacing = 0;
};

// A lattice of the scene: its sites, x fastest, then y, then z, get the ids
// first_id, first_id + 1, ... (LatticeSites makes the particle of a site).
struct LatticeSource {
  LatticeSpec spec;
  ParticleId first_id = 0;
  std::size_t count = 0;  // sites
};

}  // namespace gs
