#include "engine/step_kernels.hpp"

#include <cmath>
#include <stdexcept>

#include "backend/backend.hpp"
#include "contact/contact_time.hpp"
#include "contact/restitution.hpp"

namespace gs {

std::unique_ptr<StepKernels> make_step_kernels(const KernelChoice& c, const PairTableHost& t, int slots) {
  if (c.backend == Backend::cpu) return make_step_kernels_cpu(c, t, slots);
#ifdef GS_HAVE_CUDA
  return make_step_kernels_cuda(c, t, slots);
#else
  throw std::runtime_error("backend cuda asked for, but this grainstorm was built without the CUDA backend");
#endif
}

namespace {

// gamma = 2 zeta sqrt(m_eff k) (linear) and 2 sqrt(5/6) zeta sqrt(S m_eff)
// with S_n = 2 E* a, S_t = 8 G* a (Hertz-Mindlin): the factors in front of
// the contact's own root (contact/normal_force.hpp). zeta is that of the
// clamped normal law (contact/restitution.hpp); the tangential dashpot uses
// the same ratio.
void set_damping_factors(PairTableHost& t, std::size_t k, ContactModel model, double zeta) {
  if (model == ContactModel::linear) {
    t.damping_factor_normal[k] = 2 * zeta * std::sqrt(t.stiffness_normal[k]);
    t.damping_factor_tangential[k] = 2 * zeta * std::sqrt(t.stiffness_tangential[k]);
  } else {
    const double tsuji = 2 * std::sqrt(5.0 / 6.0) * zeta;
    t.damping_factor_normal[k] = tsuji * std::sqrt(2 * t.youngs_modulus_eff[k]);
    t.damping_factor_tangential[k] = tsuji * std::sqrt(8 * t.shear_modulus_eff[k]);
  }
}

}  // namespace

PairTableHost make_pair_table(const SceneSpec& scene) {
  const int n = int(scene.materials.size());
  PairTableHost t;
  t.n_materials = n;
  const std::size_t nn = std::size_t(n) * n;
  for (auto* v : {&t.stiffness_normal, &t.stiffness_tangential, &t.stiffness_rolling, &t.friction,
                  &t.rolling_friction, &t.cohesion, &t.youngs_modulus_eff, &t.shear_modulus_eff,
                  &t.damping_factor_normal, &t.damping_factor_tangential})
    v->assign(nn, 0.0);
  for (const PairSpec& p : scene.pairs) {
    for (const std::size_t k : {t.at(p.material_a, p.material_b), t.at(p.material_b, p.material_a)}) {
      t.stiffness_normal[k] = p.stiffness_normal;
      t.stiffness_tangential[k] = p.stiffness_tangential;
      t.stiffness_rolling[k] = p.stiffness_rolling;
      t.friction[k] = p.friction;
      t.rolling_friction[k] = p.rolling_friction;
      t.cohesion[k] = p.cohesion_energy_density;
      if (scene.model == ContactModel::hertz_mindlin) {
        const MaterialSpec& a = scene.materials[p.material_a];
        const MaterialSpec& b = scene.materials[p.material_b];
        t.youngs_modulus_eff[k] = effective_youngs_modulus(a, b);
        t.shear_modulus_eff[k] = effective_shear_modulus(a, b);
      }
      set_damping_factors(t, k, scene.model, damping_ratio(scene.model, p.restitution));
    }
  }
  return t;
}

}  // namespace gs
