#pragma once
// A particle of the scene as the store holds it: fp32 radius, mass and
// inertia, and on an fp32 state grid its position and velocities. The set-up
// and insertion during the run fill the store this way alike.
#include <cstddef>
#include <vector>

#include "contact/contact_time.hpp"
#include "core/materials.hpp"
#include "core/particle_records.hpp"
#include "scene/particle_sets.hpp"
#include "integrate/velocity_verlet.hpp"

namespace gs {

inline float stored_mass(double radius, const MaterialSpec& material) {
  return float(sphere_mass(radius, material.density));
}

// Sets entry k of every field of `r` (sized beforehand) to particle p. An
// optional field the run does not keep is empty in `r` and left so; the image
// counts, kept by periodic runs, start at zero (no face crossed yet).
inline void set_particle(ParticleRecords& r, std::size_t k, const ParticleInit& p,
                         const std::vector<MaterialSpec>& materials, bool fp32) {
  auto state = [fp32](const Vec3d& v) { return fp32 ? on_fp32_grid(v) : v; };
  const double m = sphere_mass(p.radius, materials[std::size_t(p.material)].density);
  r.id[k] = p.id;
  r.material[k] = std::uint8_t(p.material);
  r.marker[k] = p.marker;
  r.radius[k] = float(p.radius);
  r.mass[k] = float(m);
  r.inertia[k] = float(0.4 * m * p.radius * p.radius);
  r.position[k] = state(p.position);
  r.velocity[k] = state(p.velocity);
  if (!r.angular_velocity.empty()) r.angular_velocity[k] = state(p.angular_velocity);
  if (!r.orientation.empty()) r.orientation[k] = start_value<Quaternion>();
  if (!r.image.empty()) r.image[k] = start_value<ImageCount>();
  if (!r.frozen.empty()) r.frozen[k] = p.frozen;
}

}  // namespace gs
