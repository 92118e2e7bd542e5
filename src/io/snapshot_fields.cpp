#include "io/snapshot_fields.hpp"

#include <stdexcept>

namespace gs {

const std::vector<SnapshotFieldInfo>& snapshot_field_table() {
  static const std::vector<SnapshotFieldInfo> table = {
      {SnapshotField::id, "id", 1, "UInt", 4, "1"},
      {SnapshotField::material, "material", 1, "UChar", 1, "1"},
      {SnapshotField::marker, "marker", 1, "UChar", 1, "1"},
      {SnapshotField::radius, "radius", 1, "Float", 4, "m"},
      {SnapshotField::mass, "mass", 1, "Float", 4, "kg"},
      {SnapshotField::inertia, "inertia", 1, "Float", 4, "kg m^2"},
      {SnapshotField::position, "position", 3, "Float", 8, "m"},
      {SnapshotField::velocity, "velocity", 3, "Float", 8, "m/s"},
      {SnapshotField::angular_velocity, "angular_velocity", 3, "Float", 8, "rad/s"},
      {SnapshotField::orientation, "orientation", 4, "Float", 4, "1 (unit quaternion w, x, y, z)"},
      {SnapshotField::force, "force", 3, "Float", 8, "N"},
      {SnapshotField::torque, "torque", 3, "Float", 8, "N m"},
      {SnapshotField::contact_count, "contact_count", 1, "UInt", 2, "1"},
      {SnapshotField::image, "image", 3, "Int", 4, "1 (periodic box lengths crossed)"},
  };
  return table;
}

const SnapshotFieldInfo& field_info(SnapshotField f) { return snapshot_field_table().at(std::size_t(f)); }

std::vector<SnapshotField> SnapshotFields::list() const {
  std::vector<SnapshotField> out;
  for (const SnapshotFieldInfo& info : snapshot_field_table())
    if (has(info.field)) out.push_back(info.field);
  return out;
}

std::vector<std::string> SnapshotFields::names() const {
  std::vector<std::string> out;
  for (SnapshotField f : list()) out.push_back(field_info(f).name);
  return out;
}

SnapshotFields default_snapshot_fields() {
  SnapshotFields f;
  for (SnapshotField x : {SnapshotField::id, SnapshotField::material, SnapshotField::marker, SnapshotField::radius,
                          SnapshotField::velocity, SnapshotField::angular_velocity})
    f.add(x);
  return f;
}

SnapshotFields all_particle_fields() {
  SnapshotFields f;
  for (const SnapshotFieldInfo& info : snapshot_field_table())
    if (info.field != SnapshotField::contact_count && info.field != SnapshotField::image &&
        info.field != SnapshotField::orientation)
      f.add(info.field);
  return f;
}

SnapshotFields parse_snapshot_fields(const std::vector<std::string>& names) {
  SnapshotFields fields;
  for (const std::string& name : names) {
    const SnapshotFieldInfo* found = nullptr;
    for (const SnapshotFieldInfo& info : snapshot_field_table())
      if (name == info.name) found = &info;
    if (!found) {
      std::string known;
      for (const SnapshotFieldInfo& info : snapshot_field_table()) known += (known.empty() ? "" : ", ") + std::string(info.name);
      throw std::invalid_argument("unknown snapshot field '" + name + "'; known fields: " + known);
    }
    fields.add(found->field);
  }
  return fields;
}

}  // namespace gs
