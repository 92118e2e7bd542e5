#include "contact/models/hertz_mindlin.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_time.hpp"
#include "contact/restitution.hpp"
#include "contact/stable_step.hpp"

namespace gs {

namespace {
double tsuji_factor(const PairSpec& p) { return 2 * std::sqrt(5.0 / 6.0) * damping_ratio(HertzMindlin::kId, p.restitution); }
}  // namespace

HertzMindlin::Params<double> HertzMindlin::pair_params(const MaterialSpec& a, const MaterialSpec& b,
                                                       const PairSpec& p) {
  const double youngs = effective_youngs_modulus(a, b), shear = effective_shear_modulus(a, b);
  const double tsuji = tsuji_factor(p);
  return {youngs, shear, tsuji * std::sqrt(2 * youngs), tsuji * std::sqrt(8 * shear)};
}

double HertzMindlin::critical_contact_time(const std::vector<MaterialSpec>& materials, const std::vector<PairSpec>&,
                                           const std::vector<double>& r) {
  double t = std::numeric_limits<double>::infinity();
  for (std::size_t m = 0; m < materials.size(); ++m)
    if (std::isfinite(r[m]))
      t = std::min(t, rayleigh_time(r[m], materials[m].density, materials[m].youngs_modulus, materials[m].poisson_ratio));
  return t;
}

DenseBedSprings HertzMindlin::dense_bed_springs(const MaterialSpec& a, const MaterialSpec& b, const PairSpec& p,
                                                double effective_mass, double effective_radius) {
  const double contact_radius = effective_radius * std::sqrt(kHertzReferenceOverlap);
  const double normal = 2 * effective_youngs_modulus(a, b) * contact_radius;
  const double tangential = 8 * effective_shear_modulus(a, b) * contact_radius;
  const double tsuji = tsuji_factor(p);
  return {normal, tangential, p.stiffness_rolling, tsuji * std::sqrt(effective_mass / normal),
          tsuji * std::sqrt(effective_mass / tangential)};
}

}  // namespace gs
