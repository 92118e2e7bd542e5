#pragma once
// Shared helpers for tests: scenes built in code, the backends to test on.
#include <cstring>
#include <string>
#include <vector>

#include "backend/backend.hpp"
#include "engine/simulation.hpp"

namespace gs::test {

// Whether two arrays hold the same bytes (bitwise equality: -0 differs from
// +0, a NaN equals itself).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Backends the suite runs on here: cpu always, cuda when a device is present
// (GS_TEST_BACKENDS=cpu,cuda overrides).
std::vector<Backend> test_backends();
std::string backend_label(const testing::TestParamInfo<Backend>& info);

// A scene with one material "m" (and pair m-m), a domain, no particles.
SceneSpec base_scene(double density, double stiffness, double restitution, double friction = 0,
                     ContactModel model = ContactModel::linear);
ParticleInit particle(ParticleId id, double radius, Vec3d position, Vec3d velocity = {});
Wall plane_wall(Vec3d point, Vec3d normal, int material = 0);
// Adds to base_scene's a second material "n" (lighter, softer) and its pairs
// n-m and n-n, each with its own stiffnesses, restitution and friction
// (0.3 and 0.4; m-m keeps base_scene's), so that unlike pairs take the
// (m, n) entry from either side.
void add_second_material(SceneSpec& scene);

// Sets an environment variable (a run's setting) for this object's life,
// then puts back what was there (or unsets it).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value);
  ~ScopedEnv();
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;
  void set(const char* value) const;

 private:
  std::string name_, old_;
  bool had_ = false;
};

double kinetic_energy(const ParticleSnapshot& s);  // translational + rotational
double translational_kinetic_energy(const ParticleSnapshot& s);

// Mass of a sphere as the particle store keeps it (fp32, like radius and inertia).
double stored_sphere_mass(double radius, double density);

}  // namespace gs::test
