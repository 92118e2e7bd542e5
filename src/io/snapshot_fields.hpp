#pragma once
// The particle fields a snapshot holds, chosen by the scene by name. Each
// field is one dataset /particles/<name> (docs/OUTPUT.md). position is always
// written: it is the geometry every viewer needs.
#include <string>
#include <vector>

namespace gs {

enum class SnapshotField : int {
  id, material, marker, radius, mass, inertia,
  position, velocity, angular_velocity, orientation, force, torque,
  contact_count, image
};

// How a field lies in the file: dataset shape (N) or (N, components), element
// type (as XDMF names it: NumberType and Precision in bytes), units.
struct SnapshotFieldInfo {
  SnapshotField field;
  const char* name;
  int components;
  const char* number_type;  // "Float", "Int", "UInt" or "UChar"
  int precision;
  const char* units;
};

// Every field, in dataset order.
const std::vector<SnapshotFieldInfo>& snapshot_field_table();
const SnapshotFieldInfo& field_info(SnapshotField f);

class SnapshotFields {
 public:
  SnapshotFields() = default;  // position only
  bool has(SnapshotField f) const { return (bits_ >> int(f)) & 1u; }
  SnapshotFields& add(SnapshotField f) {
    bits_ |= 1u << int(f);
    return *this;
  }
  std::vector<SnapshotField> list() const;  // in dataset order
  std::vector<std::string> names() const;
  bool operator==(const SnapshotFields& o) const { return bits_ == o.bits_; }

 private:
  unsigned bits_ = 1u << int(SnapshotField::position);
};

// id, material, marker, radius, position, velocity, angular_velocity: what
// the CSV output holds.
SnapshotFields default_snapshot_fields();
// Every field but contact_count (which needs counts from the caller), image
// (which only periodic runs keep) and orientation (kept only by runs whose
// snapshots name it: core/particle_fields.hpp).
SnapshotFields all_particle_fields();

// Names to fields; position is added when missing. An unknown name throws
// std::invalid_argument naming it and listing the known ones.
SnapshotFields parse_snapshot_fields(const std::vector<std::string>& names);

}  // namespace gs
