#pragma once
// The hysteretic linear spring of Walton & Braun (1986, J. Rheol. 30, 949),
// an elasto-plastic normal law for grains that flatten where they touch
// (pharmaceutical powders and granules): loading follows k_1, unloading and
// reloading the stiffer k_2 from the permanent overlap the peak left,
//   f_n = max(0, min(k_1 delta, k_2 (delta - delta_0))),
//   delta_0 = delta_max (1 - k_1 / k_2),
// with delta_max the largest overlap of the contact so far (kept in its
// history). A lone impact rebounds at e = sqrt(k_1 / k_2), whatever its
// speed, so k_2 = k_1 / e^2 from the scene's restitution; there is no normal
// dashpot. The tangential spring is the linear model's, its dashpot with the
// damping ratio of e (contact/restitution.hpp).
#include <cmath>
#include <vector>

#include "contact/contact_model.hpp"
#include "core/types.hpp"

namespace gs {

struct HystereticLinear {
  static constexpr ContactModel kId = ContactModel::hysteretic_linear;
  static constexpr const char* kName = "hysteretic_linear";
  static constexpr unsigned kHistoryFields = kPeakOverlap;
  static constexpr bool kNeedsStiffness = true;
  static constexpr bool kNeedsElasticConstants = false;

  template <class Real>
  struct Params {
    Real stiffness_loading;          // k_1 [N/m]: the scene's stiffness_normal
    Real stiffness_unloading;        // k_2 = k_1 / e^2 [N/m]
    Real permanent_fraction;         // delta_0 / delta_max = 1 - k_1 / k_2 = 1 - e^2
    Real stiffness_tangential;       // k_t [N/m]
    Real damping_factor_tangential;  // 2 zeta sqrt(k_t)
    template <class R>
    Params<R> as() const {
      return {R(stiffness_loading), R(stiffness_unloading), R(permanent_fraction), R(stiffness_tangential),
              R(damping_factor_tangential)};
    }
  };
  template <class Real>
  struct Local {
    Real damping_root;  // sqrt(m*), for the tangential dashpot
  };

  static Params<double> pair_params(const MaterialSpec& a, const MaterialSpec& b, const PairSpec& p);

  template <class Real>
  GS_HD GS_INLINE static Local<Real> local(const Params<Real>&, Real /*overlap*/, Real effective_mass,
                                           Real /*effective_radius*/) {
    return {std::sqrt(effective_mass)};
  }
  template <class Real>
  GS_HD GS_INLINE static Real normal_force(const Params<Real>& p, Real overlap, Real /*overlap_rate*/,
                                           const Local<Real>&, ContactState<Real>& state) {
    const Real peak = state.peak_overlap > overlap ? state.peak_overlap : overlap;
    state.peak_overlap = peak;
    const Real loading = p.stiffness_loading * overlap;
    const Real unloading = p.stiffness_unloading * (overlap - p.permanent_fraction * peak);
    return repulsive_part(loading < unloading ? loading : unloading);
  }
  template <class Real>
  GS_HD GS_INLINE static TangentialCoefficients<Real> tangential(const Params<Real>& p, const Local<Real>& l) {
    return {p.stiffness_tangential, p.damping_factor_tangential * l.damping_root};
  }

  // A lone contact: a quarter period on k_1 in, a quarter on k_2 out,
  // pi/2 (sqrt(m*/k_1) + sqrt(m*/k_2)), for the smallest particles of each pair.
  static double critical_contact_time(const std::vector<MaterialSpec>& materials, const std::vector<PairSpec>& pairs,
                                      const std::vector<double>& r);
  // A dense bed oscillates on the unloading branch: k_2, without dashpot.
  static DenseBedSprings dense_bed_springs(const MaterialSpec& a, const MaterialSpec& b, const PairSpec& p,
                                           double effective_mass, double effective_radius);
};

}  // namespace gs
