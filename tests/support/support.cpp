#include <gtest/gtest.h>

#include "support/support.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace gs::test {

std::vector<Backend> test_backends() {
  std::vector<Backend> out;
  if (const char* env = std::getenv("GS_TEST_BACKENDS")) {
    std::stringstream ss(env);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(parse_backend(item));
    return out;
  }
  out.push_back(Backend::cpu);
  if (cuda_device_available()) out.push_back(Backend::cuda);
  return out;
}

std::string backend_label(const testing::TestParamInfo<Backend>& info) { return backend_name(info.param); }

SceneSpec base_scene(double density, double stiffness, double restitution, double friction, ContactModel model) {
  SceneSpec s;
  s.path = "test";
  s.domain_min = {-0.02, -0.02, -0.02};  // small: the cell grid spans the domain
  s.domain_max = {0.02, 0.02, 0.02};
  s.model = model;
  s.precision = Precision::fp64;
  MaterialSpec m;
  m.name = "m";
  m.density = density;
  m.youngs_modulus = 1e7;
  m.poisson_ratio = 0.3;
  s.materials.push_back(m);
  PairSpec p;
  p.stiffness_normal = stiffness;
  p.stiffness_tangential = stiffness * 2.0 / 7.0;
  p.stiffness_rolling = stiffness * 2.0 / 7.0;
  p.restitution = restitution;
  p.friction = friction;
  s.pairs.push_back(p);
  s.duration = 1;
  return s;
}

ParticleInit particle(ParticleId id, double radius, Vec3d position, Vec3d velocity) {
  ParticleInit p;
  p.id = id;
  p.radius = radius;
  p.position = position;
  p.velocity = velocity;
  return p;
}

Wall plane_wall(Vec3d point, Vec3d normal, int material) {
  Wall w;
  w.kind = WallKind::plane;
  w.point = point;
  w.normal = normal * (1.0 / norm(normal));
  w.material = material;
  return w;
}

void add_second_material(SceneSpec& scene) {
  MaterialSpec light = scene.materials[0];
  light.name = "n";
  light.density = 1500;
  light.youngs_modulus = 5e6;
  light.poisson_ratio = 0.25;
  scene.materials.push_back(light);
  PairSpec unlike = scene.pairs[0], like = scene.pairs[0];
  unlike.material_b = 1;
  unlike.stiffness_normal = 600;
  unlike.stiffness_tangential = 200;
  unlike.stiffness_rolling = 150;
  unlike.restitution = 0.6;
  unlike.friction = 0.3;
  like.material_a = like.material_b = 1;
  like.stiffness_normal = 800;
  like.restitution = 0.7;
  like.friction = 0.4;
  scene.pairs.push_back(unlike);
  scene.pairs.push_back(like);
}

ScopedEnv::ScopedEnv(const char* name, const char* value) : name_(name) {
  const char* v = std::getenv(name);
  had_ = v != nullptr;
  if (had_) old_ = v;
  set(value);
}
ScopedEnv::~ScopedEnv() {
  if (had_) setenv(name_.c_str(), old_.c_str(), 1);
  else unsetenv(name_.c_str());
}
void ScopedEnv::set(const char* value) const {
  if (value) setenv(name_.c_str(), value, 1);
  else unsetenv(name_.c_str());
}

double kinetic_energy(const ParticleSnapshot& s) {
  double e = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    e += 0.5 * s.mass[i] * norm2(s.velocity[i]) + 0.5 * s.inertia[i] * norm2(s.angular_velocity[i]);
  return e;
}

double translational_kinetic_energy(const ParticleSnapshot& s) {
  double e = 0;
  for (std::size_t i = 0; i < s.size(); ++i) e += 0.5 * s.mass[i] * norm2(s.velocity[i]);
  return e;
}

double stored_sphere_mass(double radius, double density) {
  return double(float(4.0 / 3.0 * M_PI * radius * radius * radius * density));
}

}  // namespace gs::test
