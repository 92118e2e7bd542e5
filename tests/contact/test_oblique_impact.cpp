// Oblique impact of a sphere on a rigid plane in the gross-sliding regime
// (Chung & Ooi 2011, test 4: alumina, |v| = 3.9 m/s, mu = 0.092), both
// models, restitution 0.3 to 1.
//
// Rigid-body analysis: while the contact point slides, the friction force is
// mu f_n against the slip, so the tangential impulse is mu times the normal
// impulse (1 + e) m v_n:
//   v_t' = v_t0 - mu (1 + e) v_n,   omega' = 5/2 mu (1 + e) v_n / R,   v_n' = e v_n,
// valid while the slip v_t - R omega stays positive to the end of the contact,
// that is for v_t0 / v_n > 7/2 mu (1 + e) (solid sphere, I = 2/5 m R^2).
// Checked: v_t', omega' and v_n' within 1 % of these, the friction force never
// along the slip, and its magnitude mu f_n at every step of the contact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/support.hpp"

namespace gs::test {
namespace {

// Chung & Ooi 2011, table 1 (alumina sphere on a plate).
constexpr double kYoungs = 380e9, kPoisson = 0.23, kDensity = 4000, kRadius = 0.00255, kMu = 0.092;
constexpr double kSpeed = 3.9;

double sphere_mass() { return 4.0 / 3.0 * M_PI * std::pow(kRadius, 3) * kDensity; }

// Hertz contact time of a sphere on a rigid plane: 2.9432 delta_max / v_n.
double hertz_contact_time(double normal_speed) {
  const double youngs_eff = kYoungs / (1 - kPoisson * kPoisson);
  const double m = sphere_mass();
  const double delta_max = std::pow(15 * m * normal_speed * normal_speed / (16 * youngs_eff * std::sqrt(kRadius)), 0.4);
  return 2.94324 * delta_max / normal_speed;
}

// Material 0: the sphere; material 1: the plate, a million times stiffer (rigid).
SceneSpec oblique_scene(ContactModel model, double e) {
  SceneSpec scene = base_scene(kDensity, 0, e, kMu, model);
  scene.effects = kFriction;
  scene.materials[0].youngs_modulus = kYoungs;
  scene.materials[0].poisson_ratio = kPoisson;
  scene.materials.push_back(scene.materials[0]);
  scene.materials[1].name = "plate";
  scene.materials[1].youngs_modulus = kYoungs * 1e6;
  // Linear: the k_n whose contact time pi sqrt(m / k_n) is Hertz's at 3.9 m/s.
  const double t_hertz = hertz_contact_time(kSpeed);
  const double k_n = sphere_mass() * M_PI * M_PI / (t_hertz * t_hertz);
  scene.pairs[0].stiffness_normal = k_n;
  scene.pairs[0].stiffness_tangential = 2.0 / 7.0 * k_n;
  scene.pairs.push_back(scene.pairs[0]);
  scene.pairs[1].material_b = 1;
  scene.walls = {plane_wall({0, 0, 0}, {0, 0, 1}, 1)};
  return scene;
}

struct ObliqueResult {
  Vec3d velocity, angular_velocity;
  int contact_steps = 0, steps_along_slip = 0, steps_below_cap = 0;
};

// Runs the sphere from just above the plane until it has left it.
ObliqueResult simulate(ContactModel model, double e, double angle, Backend backend) {
  SceneSpec scene = oblique_scene(model, e);
  const double v_n = kSpeed * std::cos(angle), v_t = kSpeed * std::sin(angle);
  const double gap = 1e-7;
  ParticleInit p = particle(0, kRadius, {0, 0, kRadius + gap}, {v_t, 0, -v_n});
  scene.particles = {p};
  const double t_c = hertz_contact_time(v_n);
  scene.time_step = t_c / 2000;
  scene.contact_time = t_c;
  Simulation sim(scene, {backend});
  ObliqueResult r;
  bool touched = false;
  for (int step = 0; step < 100000; ++step) {
    sim.run(1);
    const ParticleSnapshot s = sim.snapshot();
    const Vec3d f = s.force[0];
    const bool touching = s.position[0].z < kRadius;
    if (touching) {
      touched = true;
      ++r.contact_steps;
      // Slip of the contact point, at lever R - delta below the centre.
      const double lever = s.position[0].z;
      const double slip = s.velocity[0].x - lever * s.angular_velocity[0].y;
      if (f.x * slip > 0) ++r.steps_along_slip;
      if (f.z > 0 && std::fabs(f.x) < kMu * f.z * (1 - 1e-6)) ++r.steps_below_cap;
    }
    if (touched && !touching) break;
  }
  const ParticleSnapshot s = sim.snapshot();
  r.velocity = s.velocity[0];
  r.angular_velocity = s.angular_velocity[0];
  return r;
}

const char* model_name(ContactModel m) { return m == ContactModel::linear ? "linear" : "hertz_mindlin"; }

struct Case {
  ContactModel model;
  double angle_deg;
};

class ObliqueImpactTest : public testing::TestWithParam<Backend> {};

TEST_P(ObliqueImpactTest, GrossSlidingReboundMatchesRigidBodyTheory) {
  for (const Case c : {Case{ContactModel::linear, 35}, Case{ContactModel::linear, 45}, Case{ContactModel::linear, 70},
                       Case{ContactModel::hertz_mindlin, 35},
                       Case{ContactModel::hertz_mindlin, 45}, Case{ContactModel::hertz_mindlin, 70}}) {
    for (const double e : {0.3, 0.5, 0.7, 0.9, 1.0}) {
      const double angle = c.angle_deg * M_PI / 180;
      const double v_n = kSpeed * std::cos(angle), v_t0 = kSpeed * std::sin(angle);
      ASSERT_GT(v_t0 / v_n, 3.5 * kMu * (1 + e));  // slides throughout
      const std::string label = std::string(model_name(c.model)) + " e " + std::to_string(e) + " angle " +
                                std::to_string(c.angle_deg);
      SCOPED_TRACE(label);
      const ObliqueResult r = simulate(c.model, e, angle, GetParam());
      const double impulse = kMu * (1 + e) * v_n;  // per unit mass
      const double v_t = v_t0 - impulse, spin = 2.5 * impulse / kRadius;
      std::printf("[ measured ] %-13s e %.1f angle %2.0f: v_n'/(e v_n) %.5f  v_t'/analytic %.5f  "
                  "omega'/analytic %.5f  steps along slip %d of %d, below the cap %d\n",
                  model_name(c.model), e, c.angle_deg, r.velocity.z / (e * v_n), r.velocity.x / v_t,
                  r.angular_velocity.y / spin, r.steps_along_slip, r.contact_steps, r.steps_below_cap);
      EXPECT_NEAR(r.velocity.z / (e * v_n), 1.0, 0.01);
      EXPECT_NEAR(r.velocity.x / v_t, 1.0, 0.01);
      EXPECT_NEAR(r.angular_velocity.y / spin, 1.0, 0.01);
      EXPECT_GT(r.contact_steps, 1000);
      EXPECT_EQ(r.steps_along_slip, 0);
      EXPECT_EQ(r.steps_below_cap, 0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ObliqueImpactTest, testing::ValuesIn(test_backends()), backend_label);

}  // namespace
}  // namespace gs::test
