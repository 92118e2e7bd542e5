#pragma once
// When the CPU computes each touching pair once for both spheres
// (engine/force_kernel.hpp, pairs_of) rather than each sphere its own side.
// Once per pair pays where most list entries touch and costs where few do:
// on one core, a dense bed (4.4 contacts per sphere) stepped 5-9 % faster,
// a loosened one (0.7) 11 % slower (docs/PERFORMANCE.md, "Each pair once on
// the CPU"). Both ways give the same bits, so a run may change between them
// at any step: it computes each pair once while the touching entries per
// owned particle, counted at every such step, are at least kFrom, and each
// side otherwise, trying once per pair again every kRetryEvery steps.
#include "backend/backend.hpp"

namespace gs {

class PairsOncePolicy {
 public:
  static constexpr double kFrom = 2;  // touching list entries per owned particle (where the two ways break even)
  static constexpr long long kRetryEvery = 100;

  explicit PairsOncePolicy(PairsOnceSetting setting) : setting_(setting) {}

  // This step's way: true for each pair once.
  bool choose(long long step) const {
    if (setting_ != PairsOnceSetting::automatic) return setting_ == PairsOnceSetting::always;
    return once_ || step >= retry_at_;
  }
  // Whether counted() wants the touching entries (a pass over the list): only
  // where the choice is automatic.
  bool counts() const { return setting_ == PairsOnceSetting::automatic; }
  // After a step that computed each pair once: its touching entries per owned particle.
  void counted(double touching_per_particle, long long step) {
    once_ = touching_per_particle >= kFrom;
    if (!once_) retry_at_ = step + kRetryEvery;
  }

 private:
  PairsOnceSetting setting_;
  bool once_ = true;
  long long retry_at_ = 0;
};

}  // namespace gs
