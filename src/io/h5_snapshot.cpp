#include "io/h5_snapshot.hpp"

#include <cstdio>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/h5_io.hpp"
#include "io/h5_walls.hpp"

namespace gs {
namespace {

std::size_t field_length(const ParticleSnapshot& s, SnapshotField f, const SnapshotMetadata& m) {
  switch (f) {
    case SnapshotField::id: return s.id.size();
    case SnapshotField::material: return s.material.size();
    case SnapshotField::marker: return s.marker.size();
    case SnapshotField::radius: return s.radius.size();
    case SnapshotField::mass: return s.mass.size();
    case SnapshotField::inertia: return s.inertia.size();
    case SnapshotField::position: return s.position.size();
    case SnapshotField::velocity: return s.velocity.size();
    case SnapshotField::angular_velocity: return s.angular_velocity.size();
    case SnapshotField::orientation: return s.orientation.size();
    case SnapshotField::force: return s.force.size();
    case SnapshotField::torque: return s.torque.size();
    case SnapshotField::contact_count: return m.contact_count.size();
    case SnapshotField::image: return s.image.size();
  }
  return 0;
}

void write_field(const h5::File& f, const std::string& path, const ParticleSnapshot& s, SnapshotField field,
                 const SnapshotMetadata& m) {
  switch (field) {
    case SnapshotField::id: h5::write_vector(f, path, s.id); break;
    case SnapshotField::material: h5::write_vector(f, path, s.material); break;
    case SnapshotField::marker: h5::write_vector(f, path, s.marker); break;
    case SnapshotField::radius: h5::write_vector(f, path, s.radius); break;
    case SnapshotField::mass: h5::write_vector(f, path, s.mass); break;
    case SnapshotField::inertia: h5::write_vector(f, path, s.inertia); break;
    case SnapshotField::position: h5::write_vec3(f, path, s.position); break;
    case SnapshotField::velocity: h5::write_vec3(f, path, s.velocity); break;
    case SnapshotField::angular_velocity: h5::write_vec3(f, path, s.angular_velocity); break;
    case SnapshotField::orientation: h5::write_quaternions(f, path, s.orientation); break;
    case SnapshotField::force: h5::write_vec3(f, path, s.force); break;
    case SnapshotField::torque: h5::write_vec3(f, path, s.torque); break;
    case SnapshotField::contact_count: h5::write_vector(f, path, m.contact_count); break;
    case SnapshotField::image: h5::write_image_counts(f, path, s.image); break;
  }
}

void write_root_attributes(const h5::File& f, const ParticleSnapshot& s, const SnapshotFields& fields,
                           const SnapshotMetadata& m) {
  h5::write_string_attribute(f, "/", "kind", "grainstorm snapshot");
  h5::write_attribute(f, "/", "format_version", std::int32_t(kSnapshotFormatVersion));
  h5::write_string_attribute(f, "/", "grainstorm_version", GS_VERSION);
  h5::write_attribute(f, "/", "time", s.time);
  h5::write_attribute(f, "/", "step", std::int64_t(s.step));
  h5::write_attribute(f, "/", "scene_hash", m.scene_hash);
  h5::write_string_attribute(f, "/", "scene", m.scene_path);
  h5::write_attribute(f, "/", "particle_count", std::int64_t(s.size()));
  std::string names;
  for (const std::string& n : fields.names()) names += (names.empty() ? "" : " ") + n;
  h5::write_string_attribute(f, "/", "fields", names);
  h5::write_string_attribute(f, "/", "units", "SI: m, kg, s, N, rad");
}

template <class T>
void read_if_present(const h5::File& f, SnapshotField field, hsize_t n, std::vector<T>& into) {
  const std::string path = std::string("particles/") + field_info(field).name;
  if (h5::exists(f, path)) into = h5::read_array<T>(f, path, {n});
}

}  // namespace

ParticleSnapshot read_snapshot(const std::string& path) {
  const h5::File f = h5::File::open_read_only(path);
  if (!h5::has_attribute(f, "/", "kind") || h5::read_string_attribute(f, "/", "kind") != "grainstorm snapshot")
    throw h5::FormatError(path + ": not a grainstorm snapshot");
  ParticleSnapshot s;
  s.time = h5::read_attribute<double>(f, "/", "time");
  s.step = h5::read_attribute<std::int64_t>(f, "/", "step");
  const auto n = hsize_t(h5::read_row_count(f, "/", "particle_count", "particles/position"));
  read_if_present(f, SnapshotField::id, n, s.id);
  read_if_present(f, SnapshotField::material, n, s.material);
  read_if_present(f, SnapshotField::marker, n, s.marker);
  read_if_present(f, SnapshotField::radius, n, s.radius);
  read_if_present(f, SnapshotField::mass, n, s.mass);
  if (h5::exists(f, "particles/position")) s.position = h5::read_vec3(f, "particles/position", n);
  if (h5::exists(f, "particles/velocity")) s.velocity = h5::read_vec3(f, "particles/velocity", n);
  if (h5::exists(f, "particles/image")) s.image = h5::read_image_counts(f, "particles/image", n);
  return s;
}

std::vector<WallSurfaceInfo> read_snapshot_wall_surfaces(const std::string& path) {
  const h5::File f = h5::File::open_read_only(path);
  return read_wall_surface_info(f, "wall_surfaces");
}

std::string snapshot_h5_name(long long step) {
  char name[64];
  std::snprintf(name, sizeof(name), "particles_%010lld.h5", step);
  return name;
}

void write_snapshot(const std::string& path, const ParticleSnapshot& s, const SnapshotFields& fields,
                    const std::vector<Wall>& walls, const SnapshotMetadata& metadata) {
  for (SnapshotField field : fields.list())
    if (field_length(s, field, metadata) != s.size())
      throw std::invalid_argument("write_snapshot " + path + ": field " + field_info(field).name + " has " +
                                  std::to_string(field_length(s, field, metadata)) + " values for " +
                                  std::to_string(s.size()) + " particles");
  write_atomically(path, [&](const std::string& temporary) {
    h5::File f = h5::File::create(temporary);
    write_root_attributes(f, s, fields, metadata);
    h5::create_group(f, "particles");
    for (SnapshotField field : fields.list()) {
      const std::string dataset = std::string("particles/") + field_info(field).name;
      write_field(f, dataset, s, field, metadata);
      h5::write_string_attribute(f, dataset, "units", field_info(field).units);
    }
    write_walls(f, "walls", walls, metadata.wall_names);
    if (metadata.domain) write_wall_surfaces(f, "wall_surfaces", walls, metadata.wall_names, *metadata.domain);
    f.close();
  });
}

}  // namespace gs
