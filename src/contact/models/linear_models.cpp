// Host side of the two linear-spring models: parameters, contact time and the
// springs the time-step limit sees.
#include <cmath>

#include "contact/contact_time.hpp"
#include "contact/models/hysteretic_linear.hpp"
#include "contact/models/linear_spring_dashpot.hpp"
#include "contact/restitution.hpp"

namespace gs {

LinearSpringDashpot::Params<double> LinearSpringDashpot::pair_params(const MaterialSpec&, const MaterialSpec&,
                                                                     const PairSpec& p) {
  const double zeta = damping_ratio(kId, p.restitution);
  return {p.stiffness_normal, p.stiffness_tangential, 2 * zeta * std::sqrt(p.stiffness_normal),
          2 * zeta * std::sqrt(p.stiffness_tangential)};
}

double LinearSpringDashpot::critical_contact_time(const std::vector<MaterialSpec>& materials,
                                                  const std::vector<PairSpec>& pairs, const std::vector<double>& r) {
  return shortest_over_pairs(materials, pairs, r, [](const PairSpec& p, double m_eff) {
    return linear_contact_time(p.stiffness_normal, m_eff, p.restitution);
  });
}

DenseBedSprings LinearSpringDashpot::dense_bed_springs(const MaterialSpec&, const MaterialSpec&, const PairSpec& p,
                                                       double effective_mass, double) {
  const double zeta = damping_ratio(kId, p.restitution);
  return {p.stiffness_normal, p.stiffness_tangential, p.stiffness_rolling,
          2 * zeta * std::sqrt(effective_mass / p.stiffness_normal),
          2 * zeta * std::sqrt(effective_mass / p.stiffness_tangential)};
}

HystereticLinear::Params<double> HystereticLinear::pair_params(const MaterialSpec&, const MaterialSpec&,
                                                               const PairSpec& p) {
  const double e2 = p.restitution * p.restitution;
  const double zeta = damping_ratio(ContactModel::linear, p.restitution);
  return {p.stiffness_normal, p.stiffness_normal / e2, 1 - e2, p.stiffness_tangential,
          2 * zeta * std::sqrt(p.stiffness_tangential)};
}

double HystereticLinear::critical_contact_time(const std::vector<MaterialSpec>& materials,
                                               const std::vector<PairSpec>& pairs, const std::vector<double>& r) {
  return shortest_over_pairs(materials, pairs, r, [](const PairSpec& p, double m_eff) {
    const double loading = std::sqrt(m_eff / p.stiffness_normal);
    return M_PI / 2 * (loading + loading * p.restitution);  // sqrt(m*/k_2) = e sqrt(m*/k_1)
  });
}

DenseBedSprings HystereticLinear::dense_bed_springs(const MaterialSpec&, const MaterialSpec&, const PairSpec& p,
                                                    double effective_mass, double) {
  const double zeta = damping_ratio(ContactModel::linear, p.restitution);
  return {p.stiffness_normal / (p.restitution * p.restitution), p.stiffness_tangential, p.stiffness_rolling, 0,
          2 * zeta * std::sqrt(effective_mass / p.stiffness_tangential)};
}

}  // namespace gs
