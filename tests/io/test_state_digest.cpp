// The state digest (io/state_digest.hpp) hashes each particle's contacts by
// ascending partner id and skips slots whose springs are all +0: against
// the FNV-1a of the canonical byte sequence written out by hand, for a
// history whose slots hold the contacts in another order, with free slots
// and with a claimed slot of zero springs between them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "io/fnv1a.hpp"
#include "io/state_digest.hpp"

namespace gs {
namespace {

// Two particles (ids 9 and 4, stored in that order) with friction springs only.
ParticleSnapshot two_particles() {
  ParticleSnapshot s;
  s.step = 17;
  s.time = 0.25;
  for_each_particle_field(s, [](const char*, auto& field) { field.resize(2); });
  s.image.clear(), s.frozen.clear();  // fields this run does not keep
  s.id = {9, 4};
  s.radius = {1e-3f, 2e-3f};
  s.position = {Vec3d(0.1, 0.2, 0.3), Vec3d(-1, 0, 2)};
  s.force = {Vec3d(1, 2, 3), Vec3d(4, 5, 6)};
  s.torque = {Vec3d(0, 0, 1), Vec3d(0, 1, 0)};
  return s;
}

// Three slots each: particle 9 touches 4 and wall 0; particle 4 touches 9.
HostHistory slots_in_claim_order() {
  HostHistory h;
  h.slots = 3;
  h.partner = {kWallPartnerBase, kNoPartner, 4, kNoPartner, 9, kNoPartner};
  h.tangential = {Vec3d(0, 0, -5e-3), Vec3d(), Vec3d(1e-3, 2e-3, 0), Vec3d(), Vec3d(-1e-3, -2e-3, 0), Vec3d()};
  return h;
}

// The definition written out: step, time, count, then by ascending id each
// particle's fields (core/particle_fields.hpp order), force, torque, its
// number of contacts and each (partner, spring) by ascending partner.
std::uint64_t canonical(const ParticleSnapshot& s) {
  Fnv1a64 h;
  h.add_value(std::int64_t(s.step));
  h.add_value(s.time);
  h.add_value(std::uint64_t(2));
  auto particle = [&](std::size_t r) {
    h.add_value(s.id[r]), h.add_value(s.material[r]), h.add_value(s.marker[r]), h.add_value(s.radius[r]);
    h.add_value(s.mass[r]), h.add_value(s.inertia[r]), h.add_value(s.position[r]), h.add_value(s.velocity[r]);
    h.add_value(s.angular_velocity[r]), h.add_value(s.orientation[r]), h.add_value(s.force[r]), h.add_value(s.torque[r]);
  };
  particle(1);  // id 4
  h.add_value(std::uint64_t(1));
  h.add_value(ParticleId(9)), h.add_value(Vec3d(-1e-3, -2e-3, 0));
  particle(0);  // id 9
  h.add_value(std::uint64_t(2));
  h.add_value(ParticleId(4)), h.add_value(Vec3d(1e-3, 2e-3, 0));
  h.add_value(kWallPartnerBase), h.add_value(Vec3d(0, 0, -5e-3));
  return h.value();
}

TEST(StateDigest, ContactsCountByAscendingPartner) {
  const ParticleSnapshot s = two_particles();
  EXPECT_EQ(state_digest(s, slots_in_claim_order()), canonical(s));
}

TEST(StateDigest, AClaimedSlotWithZeroSpringsIsNoContact) {
  const ParticleSnapshot s = two_particles();
  HostHistory h = slots_in_claim_order();
  h.partner[1] = 77;  // claimed this step, springs still +0
  EXPECT_EQ(state_digest(s, h), canonical(s));
  h.tangential[1] = Vec3d(0, -0.0, 0);  // a spring of -0 is state: it can carry its sign on
  EXPECT_NE(state_digest(s, h), canonical(s));
}

TEST(StateDigest, ASpringOrPartnerChangesIt) {
  const ParticleSnapshot s = two_particles();
  HostHistory h = slots_in_claim_order();
  h.tangential[4].y = std::nextafter(h.tangential[4].y, 0.0);
  EXPECT_NE(state_digest(s, h), canonical(s));
  h = slots_in_claim_order();
  h.partner[2] = 5;
  EXPECT_NE(state_digest(s, h), canonical(s));
}

}  // namespace
}  // namespace gs
