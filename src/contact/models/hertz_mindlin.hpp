#pragma once
// Hertz-Mindlin with Tsuji-type dashpots:
//   f_n = max(0, 4/3 E* sqrt(R*) delta^(3/2) + 2 sqrt(5/6) zeta sqrt(S_n m*) delta'),
//   S_n = 2 E* a, tangential S_t = 8 G* a, damping 2 sqrt(5/6) zeta sqrt(S_t m*),
// with the contact radius a = sqrt(R* delta) and zeta from the restitution
// (the same law as the linear model's, contact/restitution.hpp).
#include <cmath>
#include <vector>

#include "contact/contact_model.hpp"
#include "core/types.hpp"

namespace gs {

struct HertzMindlin {
  static constexpr ContactModel kId = ContactModel::hertz_mindlin;
  static constexpr const char* kName = "hertz_mindlin";
  static constexpr unsigned kHistoryFields = 0;
  static constexpr bool kNeedsStiffness = false;
  static constexpr bool kNeedsElasticConstants = true;

  template <class Real>
  struct Params {
    Real youngs_modulus_eff;         // E* [Pa]
    Real shear_modulus_eff;          // G* [Pa]
    Real damping_factor_normal;      // 2 sqrt(5/6) zeta sqrt(2 E*)
    Real damping_factor_tangential;  // 2 sqrt(5/6) zeta sqrt(8 G*)
    template <class R>
    Params<R> as() const {
      return {R(youngs_modulus_eff), R(shear_modulus_eff), R(damping_factor_normal), R(damping_factor_tangential)};
    }
  };
  // The contact radius a = sqrt(R* delta), and sqrt(a m*), the root both dashpots scale with.
  template <class Real>
  struct Local {
    Real contact_radius;
    Real damping_root;
  };

  static Params<double> pair_params(const MaterialSpec& a, const MaterialSpec& b, const PairSpec& p);

  template <class Real>
  GS_HD GS_INLINE static Local<Real> local(const Params<Real>&, Real overlap, Real effective_mass,
                                           Real effective_radius) {
    const Real a = std::sqrt(effective_radius * overlap);
    return {a, std::sqrt(a * effective_mass)};
  }
  template <class Real>
  GS_HD GS_INLINE static Real normal_force(const Params<Real>& p, Real overlap, Real overlap_rate,
                                           const Local<Real>& l, ContactState<Real>&) {
    const Real elastic = Real(4) / Real(3) * p.youngs_modulus_eff * l.contact_radius * overlap;
    return repulsive_part(mul_add(p.damping_factor_normal * l.damping_root, overlap_rate, elastic));
  }
  template <class Real>
  GS_HD GS_INLINE static TangentialCoefficients<Real> tangential(const Params<Real>& p, const Local<Real>& l) {
    return {Real(8) * p.shear_modulus_eff * l.contact_radius, p.damping_factor_tangential * l.damping_root};
  }

  // The Rayleigh time of the smallest particle of each material present.
  static double critical_contact_time(const std::vector<MaterialSpec>& materials, const std::vector<PairSpec>& pairs,
                                      const std::vector<double>& r);
  // Tangent stiffnesses at the reference overlap (contact/stable_step.hpp).
  static DenseBedSprings dense_bed_springs(const MaterialSpec& a, const MaterialSpec& b, const PairSpec& p,
                                           double effective_mass, double effective_radius);
};

}  // namespace gs
