#pragma once
// What every contact model provides, and what the laws of one contact share
// whatever the model. A contact model is a policy type (src/contact/models/)
// with:
//   kId, kName          its id (core/types.hpp) and its name in scenes;
//   kHistoryFields      the history it keeps per contact (HistoryField bits)
//                       beyond the springs of the effects;
//   kNeedsStiffness,    which keys a scene's pairs and materials must give
//   kNeedsElasticConstants  (stiffness_normal; youngs_modulus, poisson_ratio);
//   Params<Real>        its parameters for one pair of materials, in the force
//                       precision, with as<R>() to convert;
//   pair_params(a, b, pair)                      host, fp64: those parameters;
//   local(params, overlap, m*, R*)               what its laws share in one contact;
//   normal_force(params, overlap, rate, local, state)   the repulsive part, >= 0;
//   tangential(params, local)                    tangential stiffness and damping;
//   critical_contact_time(materials, pairs, r)   host: the unit of a scene's step;
//   dense_bed_springs(a, b, pair, m*, R*)        host: the springs the step limit sees.
// contact/contact_models.hpp lists the models; everything else (loader,
// kernels, time step, output) reaches a model through that list.
#include <vector>

#include "core/hd.hpp"
#include "core/materials.hpp"
#include "core/particle_fields.hpp"

namespace gs {

// The history of one contact, as the force laws read and update it; a field
// the run does not keep is never touched (contact/contact_slots.hpp).
template <class Real>
struct ContactState {
#define GS_DECLARE_FIELD(name, value, bit) value<Real> name{};
  GS_HISTORY_FIELDS(GS_DECLARE_FIELD)
#undef GS_DECLARE_FIELD
};

// A history field as the partner of the contact keeps it: a vector of the
// pair turns with the normal (negated), a scalar is the pair's own.
template <class Real>
GS_HD GS_INLINE Vec3<Real> mirrored_field(const Vec3<Real>& v) {
  return -v;
}
template <class Real>
GS_HD GS_INLINE Real mirrored_field(Real s) {
  return s;
}
template <class Real>
GS_HD GS_INLINE ContactState<Real> mirrored(const ContactState<Real>& s) {
  ContactState<Real> m;
#define GS_MIRROR_FIELD(name, value, bit) m.name = mirrored_field<Real>(s.name);
  GS_HISTORY_FIELDS(GS_MIRROR_FIELD)
#undef GS_MIRROR_FIELD
  return m;
}

// max(0, f), written out so that it is the same on host and device: the
// normal laws are clamped, so that a separating contact does not pull.
template <class Real>
GS_HD GS_INLINE Real repulsive_part(Real f) {
  return f > Real(0) ? f : Real(0);
}

// Tangential stiffness and damping coefficient of a contact.
template <class Real>
struct TangentialCoefficients {
  Real stiffness;
  Real damping;
};

// What the time-step limit sees of one pair's springs (contact/stable_step.hpp):
// the stiffnesses a dense bed oscillates with, and each dashpot's beta = gamma / k.
struct DenseBedSprings {
  double normal, tangential, rolling;
  double beta_normal, beta_tangential;
};

// The parameters of one pair of materials as the kernels read them: the
// model's own, then those of the effects, which every model shares.
template <class Real, class Model>
struct PairParams {
  typename Model::template Params<Real> model;
  Real stiffness_rolling;  // k_r [N/m], rolling spring (constant over a contact)
  Real friction;           // Coulomb coefficient mu
  Real rolling_friction;   // dimensionless mu_r: rolling torque cap mu_r R_eff f_n
  Real cohesion;           // cohesion energy density k_c [N/m^2]: f = k_c * contact area
};

// Read-only view of the symmetric pair table, n_materials^2 entries.
template <class Real, class Model>
struct PairTable {
  const PairParams<Real, Model>* params;
  int n_materials;
  GS_HD const PairParams<Real, Model>& operator()(int a, int b) const { return params[a * n_materials + b]; }
};

// The table of every pair of materials (zero for pairs the scene leaves out:
// they never touch), entry (a, b) at a * n + b, in precision Real. The
// parameters are derived in fp64 and rounded once.
template <class Real, class Model>
std::vector<PairParams<Real, Model>> make_pair_table(const std::vector<MaterialSpec>& materials,
                                                    const std::vector<PairSpec>& pairs) {
  const std::size_t n = materials.size();
  std::vector<PairParams<Real, Model>> table(n * n, PairParams<Real, Model>{});
  for (const PairSpec& p : pairs) {
    PairParams<Real, Model> e;
    e.model = Model::pair_params(materials[p.material_a], materials[p.material_b], p).template as<Real>();
    e.stiffness_rolling = Real(p.stiffness_rolling);
    e.friction = Real(p.friction);
    e.rolling_friction = Real(p.rolling_friction);
    e.cohesion = Real(p.cohesion_energy_density);
    table[std::size_t(p.material_a) * n + std::size_t(p.material_b)] = e;
    table[std::size_t(p.material_b) * n + std::size_t(p.material_a)] = e;
  }
  return table;
}

}  // namespace gs
