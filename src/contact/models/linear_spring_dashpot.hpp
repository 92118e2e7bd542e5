#pragma once
// The linear spring-dashpot (seed Eq. 8; Luding 1998):
//   f_n = max(0, k_n delta + gamma_n delta'),  gamma_n = 2 zeta sqrt(m* k_n),
//   tangential k_t with gamma_t = 2 zeta sqrt(m* k_t),
// zeta from the restitution for the clamped law (contact/restitution.hpp).
#include <cmath>
#include <vector>

#include "contact/contact_model.hpp"
#include "core/types.hpp"

namespace gs {

struct LinearSpringDashpot {
  static constexpr ContactModel kId = ContactModel::linear;
  static constexpr const char* kName = "linear";
  static constexpr unsigned kHistoryFields = 0;
  static constexpr bool kNeedsStiffness = true;
  static constexpr bool kNeedsElasticConstants = false;

  template <class Real>
  struct Params {
    Real stiffness_normal;           // k_n [N/m]
    Real stiffness_tangential;       // k_t [N/m]
    // gamma = factor * sqrt(m*): the constant part of the root is taken once
    // per pair, so a contact takes one square root for both dashpots.
    Real damping_factor_normal;      // 2 zeta sqrt(k_n)
    Real damping_factor_tangential;  // 2 zeta sqrt(k_t)
    template <class R>
    Params<R> as() const {
      return {R(stiffness_normal), R(stiffness_tangential), R(damping_factor_normal), R(damping_factor_tangential)};
    }
  };
  // sqrt(m*), which both dashpots scale with.
  template <class Real>
  struct Local {
    Real damping_root;
  };

  static Params<double> pair_params(const MaterialSpec& a, const MaterialSpec& b, const PairSpec& p);

  template <class Real>
  GS_HD GS_INLINE static Local<Real> local(const Params<Real>&, Real /*overlap*/, Real effective_mass,
                                           Real /*effective_radius*/) {
    return {std::sqrt(effective_mass)};
  }
  template <class Real>
  GS_HD GS_INLINE static Real normal_force(const Params<Real>& p, Real overlap, Real overlap_rate,
                                           const Local<Real>& l, ContactState<Real>&) {
    const Real gamma_n = p.damping_factor_normal * l.damping_root;
    return repulsive_part(mul_add(p.stiffness_normal, overlap, gamma_n * overlap_rate));
  }
  template <class Real>
  GS_HD GS_INLINE static TangentialCoefficients<Real> tangential(const Params<Real>& p, const Local<Real>& l) {
    return {p.stiffness_tangential, p.damping_factor_tangential * l.damping_root};
  }

  // The clamped contact's duration for the smallest particles of each pair
  // (linear_contact_time, contact/contact_time.hpp); r: the smallest radius of
  // each material's particles, infinite for a wall material.
  static double critical_contact_time(const std::vector<MaterialSpec>& materials, const std::vector<PairSpec>& pairs,
                                      const std::vector<double>& r);
  static DenseBedSprings dense_bed_springs(const MaterialSpec& a, const MaterialSpec& b, const PairSpec& p,
                                           double effective_mass, double effective_radius);
};

}  // namespace gs
