#pragma once
// The largest time step at which every contact spring and dashpot of a scene
// stays stable in a dense bed, and which of them sets it (docs/STABILITY.md,
// "The time-step limit").
//
// The integrator (integrate/velocity_verlet.hpp) kicks with forces whose
// dashpots see the half-step velocity. For one mode x'' = -lambda x - c x'
// that is leapfrog with a lagged damping term, stable while
//   h^2 lambda + 2 h c < 4.
// A dashpot proportional to its spring (c = beta lambda, beta = gamma / k)
// makes this lambda (h^2 + 2 h beta) < 4, so the stiffest mode of each spring
// family binds. A lone contact has lambda = k / m_eff; in a bed a particle
// is pressed by up to Z = 12 neighbours (the kissing number of equal
// spheres) and the stiffest collective modes are those of the face-centred
// cubic packing, computed from its dynamical matrix with translations and
// rotations (checked in tests/contact/test_stable_step.cpp):
//   normal springs, neighbours pushing in antiphase:
//     lambda_n = Z/3 k_n (1/m_a + 1/m_b)
//   tangential springs, every particle turning the same way (gear mode), or
//   sliding in antiphase, whichever is stiffer:
//     lambda_t = 2Z/3 k_t max(r_a^2/I_a + r_b^2/I_b, 1/m_a + 1/m_b)
//   rolling springs, neighbours counter-rotating:
//     lambda_r = 2Z/3 k_r R*^2 (1/I_a + 1/I_b)
// A wall is a partner of infinite mass and inertia. Under Hertz-Mindlin the
// springs stiffen with the overlap; the limit takes their tangent stiffness
// at an overlap of kHertzReferenceOverlap R* (contact radius 0.1 R*, where
// Hertz theory itself stops applying).
#include <string>

#include "contact/contact_scene.hpp"

namespace gs {

// Contacts pressing one particle in the densest packing of equal spheres.
constexpr double kDenseBedCoordination = 12;

// Overlap / R* at which the Hertz-Mindlin limit takes the tangent stiffnesses.
constexpr double kHertzReferenceOverlap = 0.01;

struct StableStep {
  double time_step = 0;  // [s]
  std::string binding;   // the spring that sets it, e.g. "tangential spring of [glass, glass]"
};

// Largest stable step of one mode family: lambda (h^2 + 2 h beta) = 4.
double stable_step_of_mode(double lambda, double beta);

// The smallest of the limits of every spring of every pair of materials that
// can touch, with the smallest particles of each material in the scene.
StableStep stable_time_step(const ContactScene& scene);

}  // namespace gs
