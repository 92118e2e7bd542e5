#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/fill_region.hpp"
#include "scene/scene.hpp"

namespace gs {

// A generator could not do what was asked (e.g. the region is too full). The
// scene loader adds the file, line and key to the message.
struct GenerateError : std::runtime_error {
  using std::runtime_error::runtime_error;
  GenerateError(const std::string& what, std::size_t set_first) : std::runtime_error(what), set_first(set_first) {}
  // Index of the first particle of the set that failed, when known (the
  // loader names that set's line); kUnknown otherwise.
  static constexpr std::size_t kUnknown = std::size_t(-1);
  std::size_t set_first = kUnknown;
};

// Number of lattice sites along one axis of [lo, hi] (0 when hi < lo), and
// in all; GenerateError when more than the particle ids.
std::size_t lattice_sites(double lo, double hi, double spacing);
std::size_t lattice_count(const LatticeSpec& spec);

// Appends the lattice to `out`; ids continue from out.size().
void generate_lattice(const LatticeSpec& spec, std::vector<ParticleInit>& out);

// Particle `id` of a generated set: the template's properties at `position`.
ParticleInit make_particle(const ParticleTemplate& t, std::size_t id, const Vec3d& position, double radius);

// GenerateError when `count` more particles after `existing` ones would
// exceed the particle ids.
void check_id_room(std::size_t existing, std::size_t count);


// Radii of a random fill, largest first. A class distribution is split by the
// largest-remainder method, so each class gets round(fraction * count) particles.
std::vector<double> random_fill_radii(const SizeSpec& size, std::size_t count, std::uint64_t seed);

// Appends the random fill's `count` spheres (scene/fill_blocks.hpp: block by
// block, each block by random sequential addition, largest first), so that
// they overlap neither each other nor any sphere already in `out` (earlier
// sets). The same seed gives the same fill on every platform and for any
// rank count. Ids continue from out.size(). Throws GenerateError when the
// region is too full.
void generate_random_fill(const RandomFillSpec& spec, std::vector<ParticleInit>& out);

// Calls its argument for every sphere of the earlier sets (obstacles to a fill).
using SphereVisitor = std::function<void(const ParticleInit&)>;
using EarlierSpheres = std::function<void(const SphereVisitor&)>;

// The same with the earlier sets visited by `earlier` rather than held in
// `out`; ids start at first_id.
void generate_random_fill(const RandomFillSpec& spec, const EarlierSpheres& earlier, std::size_t first_id,
                          std::vector<ParticleInit>& out);

// Finds one pair of overlapping spheres (centre distance below the sum of the
// radii by more than a relative `tolerance`), first < second. Returns false
// when there is none. Throws GenerateError beyond 2e8 spheres.
bool find_overlap(const std::vector<ParticleInit>& particles, std::size_t& first, std::size_t& second,
                  double tolerance = 1e-9);

}  // namespace gs
