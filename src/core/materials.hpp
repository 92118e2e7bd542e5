#pragma once
// Materials and the contact parameters of pairs of them, as a scene gives
// them (src/scene reads them; the contact models of src/contact reduce them
// to what their force laws use).
#include <string>

namespace gs {

struct MaterialSpec {
  std::string name;
  double density = 0;          // [kg/m^3]
  double youngs_modulus = 0;   // [Pa], Hertz-Mindlin only
  double poisson_ratio = 0;    // [-], Hertz-Mindlin only
};

// Contact parameters of a pair of materials as written in the scene.
struct PairSpec {
  int material_a = 0, material_b = 0;
  double stiffness_normal = 0;       // linear models [N/m] (the hysteretic one: loading)
  double stiffness_tangential = 0;   // linear models [N/m]
  double stiffness_rolling = 0;      // rolling spring [N/m]
  double restitution = 1;            // normal coefficient of restitution in (0,1]
  double friction = 0;               // sliding friction mu >= 0
  double rolling_friction = 0;       // rolling friction mu_r >= 0
  double cohesion_energy_density = 0;// [N/m^2]
};

}  // namespace gs
