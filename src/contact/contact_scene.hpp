#pragma once
// What the time step of a scene depends on, without the scene itself
// (src/scene builds it: scene/scene_time_step.hpp): the contact model, the
// effects, the materials and pairs, and the smallest particle of each
// material, the fastest to respond.
#include <vector>

#include "core/materials.hpp"
#include "core/types.hpp"

namespace gs {

struct ContactScene {
  ContactModel model = ContactModel::linear;
  unsigned effects = 0;
  std::vector<MaterialSpec> materials;
  std::vector<PairSpec> pairs;
  std::vector<double> smallest_radius;  // per material; infinite for one without particles (a wall's)
};

}  // namespace gs
