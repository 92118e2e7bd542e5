#include "contact/stable_step.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "contact/contact_models.hpp"
#include "contact/contact_time.hpp"
#include "contact/restitution.hpp"

namespace gs {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The smallest particle of one material, the fastest to respond: its inverse
// mass, inverse moment of inertia (solid sphere, 2/5 m r^2) and radius. A
// material without particles is a wall's: immobile.
struct Body {
  double inverse_mass = 0, inverse_inertia = 0, radius = kInf;
  bool moves() const { return inverse_mass > 0; }
};

std::vector<Body> smallest_bodies(const ContactScene& s) {
  std::vector<Body> bodies(s.materials.size());
  for (std::size_t m = 0; m < bodies.size(); ++m) {
    Body& b = bodies[m];
    b.radius = s.smallest_radius[m];
    if (!std::isfinite(b.radius)) continue;
    const double mass = sphere_mass(b.radius, s.materials[m].density);
    b.inverse_mass = 1 / mass;
    b.inverse_inertia = 1 / (0.4 * mass * b.radius * b.radius);
  }
  return bodies;
}

DenseBedSprings springs_of(const ContactScene& s, const PairSpec& p, double effective_mass, double effective_radius) {
  return with_contact_model(s.model, [&](auto model) {
    return decltype(model)::dense_bed_springs(s.materials[p.material_a], s.materials[p.material_b], p, effective_mass,
                                              effective_radius);
  });
}

struct Candidate {
  double time_step;
  const char* spring;
};

// The limits of one pair's springs in a dense bed (the header's lambdas).
std::vector<Candidate> pair_limits(const ContactScene& s, const PairSpec& p, const Body& a, const Body& b) {
  const double z = kDenseBedCoordination;
  const double inverse_mass = a.inverse_mass + b.inverse_mass;
  const double lever = a.radius * a.radius * a.inverse_inertia + b.radius * b.radius * b.inverse_inertia;
  const double effective_mass = 1 / inverse_mass;
  const double effective_radius = b.moves() ? a.radius * b.radius / (a.radius + b.radius) : a.radius;
  const DenseBedSprings k = springs_of(s, p, effective_mass, effective_radius);
  std::vector<Candidate> limits;
  limits.push_back({stable_step_of_mode(z / 3 * k.normal * inverse_mass, k.beta_normal), "normal spring"});
  if ((s.effects & kFriction) && p.friction > 0)
    limits.push_back({stable_step_of_mode(2 * z / 3 * k.tangential * std::max(lever, inverse_mass),
                                          k.beta_tangential),
                      "tangential spring (with rotation)"});
  if ((s.effects & kRollingResistance) && p.rolling_friction > 0)
    limits.push_back({stable_step_of_mode(2 * z / 3 * k.rolling * effective_radius * effective_radius *
                                              (a.inverse_inertia + b.inverse_inertia),
                                          0),
                      "rolling spring"});
  return limits;
}

}  // namespace

double stable_step_of_mode(double lambda, double beta) { return std::sqrt(beta * beta + 4 / lambda) - beta; }

StableStep stable_time_step(const ContactScene& s) {
  const std::vector<Body> bodies = smallest_bodies(s);
  StableStep best{kInf, "no contact can form"};
  for (const PairSpec& p : s.pairs) {
    const Body* a = &bodies[p.material_a];
    const Body* b = &bodies[p.material_b];
    if (!a->moves()) std::swap(a, b);
    if (!a->moves()) continue;  // two wall materials never touch
    for (const Candidate& c : pair_limits(s, p, *a, *b))
      if (c.time_step < best.time_step)
        best = {c.time_step, std::string(c.spring) + " of [" + s.materials[p.material_a].name + ", " +
                                 s.materials[p.material_b].name + "]"};
  }
  return best;
}

}  // namespace gs
