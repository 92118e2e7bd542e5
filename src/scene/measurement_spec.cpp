#include "scene/measurement_spec.hpp"

#include <algorithm>

namespace gs {

bool AverageSpec::needs_contacts() const {
  return std::any_of(quantities.begin(), quantities.end(), [](AverageQuantity q) {
    return q == AverageQuantity::coordination || q == AverageQuantity::stress;
  });
}

bool MeasurementsSpec::needs_contacts() const {
  return std::any_of(averages.begin(), averages.end(), [](const AverageSpec& a) { return a.needs_contacts(); });
}

const char* quantity_name(AverageQuantity q) {
  switch (q) {
    case AverageQuantity::solid_fraction: return "solid_fraction";
    case AverageQuantity::velocity: return "velocity";
    case AverageQuantity::granular_temperature: return "granular_temperature";
    case AverageQuantity::coordination: return "coordination";
    case AverageQuantity::stress: return "stress";
  }
  return "?";
}

const std::vector<AverageQuantity>& all_quantities() {
  static const std::vector<AverageQuantity> all = {AverageQuantity::solid_fraction, AverageQuantity::velocity,
                                                   AverageQuantity::granular_temperature,
                                                   AverageQuantity::coordination, AverageQuantity::stress};
  return all;
}

}  // namespace gs
