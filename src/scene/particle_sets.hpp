#pragma once
// The scene's particles as sets: one particle, the properties a generated set
// shares, and a lattice kept as its description.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "core/vec3.hpp"
#include "scene/fill_region.hpp"

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

// A random fill: `count` spheres of `size` placed at random in `region`
// (scene/fill_blocks.hpp says how).
struct RandomFillSpec {
  ParticleTemplate tmpl;
  FillRegion region;
  std::size_t count = 0;
  SizeSpec size;
  std::uint64_t seed = 0;
  int max_attempts = 5000;  // overlap tests per particle before giving up
};

// The blocks a random fill is cut into: nx × ny × nz equal boxes over the
// region's bounds (x fastest); block b holds the fill's particles
// start[b] .. start[b + 1] - 1, each block filled on its own.
struct FillBlocks {
  Vec3d lo, hi;        // the region's bounds
  int n[3] = {1, 1, 1};
  std::vector<std::size_t> start;  // blocks + 1 entries
  std::size_t count() const { return start.size() - 1; }
};

// A random fill of the scene, kept as its description: its particles get the
// ids first_id, first_id + 1, ... block by block, and are generated where
// they are needed (scene/particle_sources.hpp).
struct RandomFillSource {
  RandomFillSpec spec;
  ParticleId first_id = 0;
  std::size_t count = 0;
  FillBlocks blocks;
};

// Where a set of particles was defined, for errors found after the scene
// was loaded (the packing checks of a run's ranks): the set's particles from
// `first` up to the next set's, at `line` of the scene file under `key`
// (a key path, e.g. particles[1].random_fill).
struct ParticleSetOrigin {
  std::size_t first = 0;
  int line = 1;
  std::string key;
};

}  // namespace gs
