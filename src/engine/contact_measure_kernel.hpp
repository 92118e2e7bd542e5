#pragma once
// The measurements' contact pass (docs/MEASUREMENTS.md): per owned particle,
// its particle contacts and its share of the contact stress
// (core/contact_measure.hpp). Run only at the steps a coordination or stress
// average is due, after that step's force computation: the same candidates in
// the same canonical order, the same kinematics (ForceKernel's) and the same
// contact law (contact_load), on the springs the step has just stored, with no
// increment (dt = 0) and nothing written back, so that a measurement never
// changes the run.
#include "core/contact_measure.hpp"
#include "engine/force_kernel.hpp"

namespace gs {

template <class Real, class Model, unsigned Effects, class Candidates>
struct ContactMeasureKernel {
  using Forces = ForceKernel<Real, Model, Effects, Candidates>;
  Forces forces;         // read only: particles, candidates, pair table, walls, history
  ContactMeasure* out;   // per owned particle

  GS_HD void operator()(Index i) const {
    ContactMeasure m;
    const Vec3d xi = forces.position[i];
    Visitor visit{this, i, xi, &m};
    forces.candidates.for_each(i, xi, visit);
    const double ri = forces.radius[i];
    for (int w = 0; w < forces.n_walls; ++w)
      if (wall_may_touch(forces.wall_screens[w], xi, ri)) add_wall(i, w, xi, m);
    out[i] = m;
  }

 private:
  struct Visitor {
    const ContactMeasureKernel* kernel;
    Index i;
    Vec3d xi;
    ContactMeasure* m;
    GS_HD void operator()(Index j, ListOffset entry) const {
      if (j != i) kernel->add_particle(i, j, entry, xi, *m);
    }
  };

  // The springs the force computation stored for this surface contact (none: zero).
  GS_HD ContactState<Real> stored_state(Index i, ParticleId partner) const {
    ContactState<Real> state;
    if constexpr (Forces::kHistory) {
      const int slot = forces.surface_history.find(i, partner);
      if (slot >= 0) state = forces.surface_history.load(i, slot);
    }
    return state;
  }

  // Each particle of a contact holds half its branch vector x_i - x_j (to
  // the nearest image of j on the axes that wrap). The pair's springs: its
  // list entry's.
  GS_HD void add_particle(Index i, Index j, ListOffset entry, const Vec3d& xi, ContactMeasure& m) const {
    ContactKinematics<Real> k;
    if (!forces.particle_kinematics(i, j, xi, k)) return;
    ContactState<Real> state;
    if constexpr (Forces::kHistory) state = forces.pair_history.load(entry);
    const ContactLoad<Real> load = contact_load<Real, Model, Effects>(
        forces.pairs(forces.material[i], forces.material[j]), k, state, Real(0));
    m.stress_moment += outer(forces.box.separation(xi, forces.position[j]) * 0.5, Vec3d(load.force));
    ++m.contacts;
  }

  // A wall takes no share: the whole branch from the contact point to the centre.
  GS_HD void add_wall(Index i, int w, const Vec3d& xi, ContactMeasure& m) const {
    WallContact wc;
    if (!wall_contact(forces.walls[w], xi, double(forces.radius[i]), wc)) return;
    const ContactKinematics<Real> k = forces.surface_kinematics(i, wc.overlap, wc.normal, wc.wall_velocity,
                                                                forces.walls[w].angular_velocity);
    ContactState<Real> state = stored_state(i, kWallPartnerBase + ParticleId(w));
    const ContactLoad<Real> load = contact_load<Real, Model, Effects>(
        forces.pairs(forces.material[i], forces.walls[w].material), k, state, Real(0));
    m.stress_moment += outer(xi - wc.point, Vec3d(load.force));
  }
};

}  // namespace gs
