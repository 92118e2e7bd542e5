#pragma once
// Contact forces, one thread per owned particle (as the seed). Each thread
// sums its particle's contacts in one canonical order, independent of thread
// scheduling and of how particles are split across ranks: first the particle
// partners in the order the candidate source gives them (CellCandidates:
// cell by cell in a fixed order, by ascending id in a cell; ListCandidates:
// by ascending id), then the walls in scene order, then triangle meshes, their
// contacts in ascending triangle order of the particle's near list
// (walls/mesh_near.hpp: the same contacts as its mesh cell's). On a GPU
// a small scene gives each particle a group of lanes instead (in_group): the
// same contacts, added in the same order, so the same bits; one thread per
// particle in a scene without a mesh runs WithoutMeshes, the same work with
// the mesh path compiled out. The CPU may
// compute each touching pair once for both spheres instead (pairs_of, then
// sum_entries; engine/pairs_once_policy.hpp says when): the same bits again.
#include <type_traits>

#include "contact/contact_models.hpp"
#include "contact/contact_slots.hpp"
#include "contact/pair_springs.hpp"
#include "core/bits.hpp"
#include "neighbor/cell_list.hpp"
#include "neighbor/verlet_list.hpp"
#include "walls/mesh_near.hpp"
#include "walls/sphere_triangle.hpp"
#include "walls/sphere_triangle_group.hpp"
#include "walls/wall_geometry.hpp"
#include "walls/wall_screen.hpp"

namespace gs {

// Where each touching pair of owned particles is computed once for both of
// its spheres (ForceKernel::pairs_of, then sum_entries: the CPU), what the
// first pass leaves per Verlet list entry for the second.
template <class Real>
struct EntryLoads {
  ContactLoad<Real>* load;    // on the row's particle, where touching
  std::uint8_t* touching;     // 1 where the pair touches
  const ListOffset* reverse;  // the partner's entry that names the row's particle (neighbor/verlet_list.hpp)
  Index n_owned;              // partners from here on are ghosts
};

// The partners whose pairs a call of pairs_of computes: a rank computes the
// pairs among its owned particles while the ghosts' fields travel.
enum class PairsOf { owned, ghosts, all };

template <class Real, class Model, unsigned Effects, class Candidates = CellCandidates>
struct ForceKernel {
  // Particles (owned and ghosts)
  const ParticleId* id;
  const std::uint8_t* material;
  const float* radius;
  const float* mass;
  const Vec3d* position;
  const Vec3d* velocity;
  const Vec3d* angular_velocity;  // null where the run keeps none (core/particle_fields.hpp)
  Candidates candidates;  // contact partners of a particle, in canonical order
  PeriodicBox box;        // separations to the nearest image on the axes that wrap
  // Interactions
  PairTable<Real, Model> pairs;
  const Wall* walls;
  const WallScreen* wall_screens;  // per wall: the first, cheap test
  int n_walls;
  MeshView meshes;          // n_triangles == 0: the scene has no mesh, the loop is skipped
  MeshNearView mesh_near;   // per owned particle: the triangles it may touch (walls/mesh_near.hpp)
  MeshLoad* mesh_load;      // per owned particle x mesh: its load on the mesh; null without meshes
  // Contact history: of particle pairs, one entry per Verlet list entry; of
  // walls and mesh features, a few slots per particle keyed by partner id.
  PairSprings<Real, history_fields_kept<Model>(Effects)> pair_history;
  SlotTable<Real, history_fields_kept<Model>(Effects)> surface_history;
  int contact_slots;  // the most contacts a particle's row holds (messages, checkpoints)
  // Outputs
  Vec3<Real>* force;
  Vec3<Real>* torque;  // null when no effect makes torques
  Real dt;
  Fault* fault;
  long long step;

  static constexpr bool kTorque = makes_torques(Effects);
  static constexpr bool kHistory = history_fields_kept<Model>(Effects) != 0;
  // GPU launch hints (backend/launch_hints.hpp). With history, four blocks
  // of 128 threads resident per multiprocessor, which caps the kernel at
  // 128 registers: the mesh path, which most threads never take, had raised
  // the frictional kernel to 132 registers and so to three blocks, a quarter
  // of the warps, and 17 % of the throughput of a bed without meshes; six or
  // eight blocks made it slower again. Without history the kernel, bound
  // by the latency of its partners' gathers too, gains from more resident
  // warps: eight blocks (64 registers) cut its time by a quarter, but made
  // a small scene's groups of lanes slower, so they keep four
  // (docs/PERFORMANCE.md, "The next partner ahead, and the frictionless
  // kernel at eight blocks").
  static constexpr int kMinBlocksPerSM = kHistory ? 4 : 8;
  static constexpr int kGroupBlocksPerSM = 4;
  static constexpr int kAnySlot = -2;  // apply(): find the contact's surface slot, or claim one
  // Mesh contacts without a slot wait until the others have taken theirs (at
  // most this many per particle; more claim a slot at once).
  static constexpr int kWaitingMeshContacts = 4;

  GS_HD GS_INLINE void operator()(Index i) const { contacts<true>(i); }

  // operator()'s work, with the mesh path compiled in or out (WithoutMeshes).
  template <bool Meshes>
  GS_HD GS_INLINE void contacts(Index i) const {
    ContactLoad<Real> total;
    unsigned touched = 0;
    int pairs_touching = 0;
    const Vec3d xi = position[i];
    if constexpr (std::is_same_v<Candidates, ListCandidates>) {
      pairs_touching = add_list_contacts(i, xi, total);
    } else {
      ParticleVisitor visit{this, i, xi, &total, &pairs_touching};
      candidates.for_each(i, xi, visit);
    }
    add_wall_contacts(i, xi, total, touched);
    // One uniform branch per particle when the scene has no mesh (docs/MESHES.md, cost).
    if constexpr (Meshes) {
      if (meshes.n_triangles > 0) add_mesh_contacts(i, xi, total, touched);
    }
    finish(i, total, touched, pairs_touching);
  }

#if defined(__CUDACC__)
  // The same as operator(), by a group of g.size GPU lanes
  // (backend/cuda/lane_group.cuh): lane r computes the contacts of list
  // entries r, r + g.size, ...; every lane then adds the touching ones in
  // list order, the additions of operator()'s loop one for one, so that the
  // force has the same bits. The lanes scan the mesh's triangles together;
  // lane 0 alone adds the walls and the mesh contacts, keeps their history
  // and writes the result. For scenes too small to fill the GPU with one
  // thread per particle, whose step lasts as long as the longest particle.
  template <class Group>
  __device__ void in_group(Index i, const Group& g) const {
    static_assert(std::is_same_v<Candidates, ListCandidates>, "lanes share out a particle's Verlet list entries");
    ContactLoad<Real> total;
    int pairs_touching = 0;
    const Vec3d xi = position[i];
    const ListOffset end = candidates.begin[i + 1];
    for (ListOffset first = candidates.begin[i]; first < end; first += ListOffset(g.size)) {
      const ListOffset k = first + ListOffset(g.rank);
      ContactLoad<Real> load;
      bool touching = false;
      if (k < end && candidates.list[k] != i) touching = particle_contact(i, candidates.list[k], k, xi, load);
      unsigned touched = g.ballot(touching);
      pairs_touching += bit_count(touched);
      for (; touched != 0; touched &= touched - 1) add_to(total, shuffled(g, load, lowest_bit(touched)));
    }
    unsigned touched = 0;
    if (g.leader()) add_wall_contacts(i, xi, total, touched);
    if (meshes.n_triangles > 0) {
      MeshContact waiting[kWaitingMeshContacts];
      int n_waiting = 0;
      if (g.leader()) clear_mesh_load(i);
      MeshContactVisitor visit{this, i, xi, &total, &touched, waiting, &n_waiting};
      const ListOffset first = mesh_near.begin[i];
      const std::int32_t count = std::int32_t(mesh_near.begin[i + 1] - first);
      for_each_near_mesh_contact_in_group(meshes, mesh_near.triangles + first, count, xi, double(radius[i]), g,
                                          visit);  // visits on lane 0 only
      if (g.leader()) add_waiting_mesh_contacts(i, xi, waiting, n_waiting, total, touched);
    }
    if (g.leader()) finish(i, total, touched, pairs_touching);
  }
#endif

  // Each pair once, first pass: the pairs of particle i's list entries that
  // i computes. With an owned partner j > i whose row names i, for both
  // (pair_once): j's load and springs are those j's own computation would
  // give, bit for bit (the law is antisymmetric, particle_kinematics; the
  // springs' zeros are stored +0, contact/pair_springs.hpp); such a pair
  // with j < i is j's to compute. With a ghost (or a partner whose row does
  // not name i), i's side alone, as operator() does.
  GS_HD void pairs_of(Index i, PairsOf which, const EntryLoads<Real>& e) const {
    static_assert(std::is_same_v<Candidates, ListCandidates>, "pairs are computed per Verlet list entry");
    const Vec3d xi = position[i];
    for (ListOffset k = candidates.begin[i]; k < candidates.begin[i + 1]; ++k) {
      const Index j = candidates.list[k];
      const bool owned = j < e.n_owned;
      if (which == (owned ? PairsOf::ghosts : PairsOf::owned)) continue;
      const ListOffset r = owned ? e.reverse[k] : kNoEntry;
      if (r == kNoEntry) e.touching[k] = particle_contact(i, j, k, xi, e.load[k]) ? 1 : 0;
      else if (j > i) pair_once(i, j, k, r, xi, e);
    }
  }

  // Each pair once, second pass: particle i's sums from its entries' loads,
  // in list order, then its walls and meshes, as operator() adds them: the
  // same bits.
  GS_HD void sum_entries(Index i, const EntryLoads<Real>& e) const {
    int pairs_touching = 0;
    ContactLoad<Real> total = entries_sum(i, e, pairs_touching);
    unsigned touched = 0;
    const Vec3d xi = position[i];
    add_wall_contacts(i, xi, total, touched);
    if (meshes.n_triangles > 0) add_mesh_contacts(i, xi, total, touched);
    finish(i, total, touched, pairs_touching);
  }

  // The sum of i's touching entries' loads, in list order, and their count.
  // Its own function, so that the running sum stays in registers (the
  // total that the walls' functions take by reference lives in memory).
  GS_HD GS_INLINE ContactLoad<Real> entries_sum(Index i, const EntryLoads<Real>& e, int& touching) const {
    ContactLoad<Real> sum;
    int n = 0;
    for (ListOffset k = candidates.begin[i]; k < candidates.begin[i + 1]; ++k) {
      if (!e.touching[k]) continue;
      add_to(sum, e.load[k]);
      ++n;
    }
    touching = n;
    return sum;
  }

  // Whether particles i (at xi) and j overlap, and if so the kinematics of
  // their contact as seen from i. Public for the measurements' contact pass
  // (engine/contact_measure_kernel.hpp), which must see the same contacts.
  // Seen from j every quantity is exactly the negation (the normal, the
  // velocities) or exactly the same (overlap, effective mass and radius),
  // and the law negates every rounded step with its inputs, so the two
  // spheres of a contact get exactly opposite forces (Newton's third law with
  // no rounding left over; tests/physics/test_newton_third_law.cpp). Hence
  // the two levers' spins are summed with each product rounded on its own: a
  // fused mul_add(wi, lever_i, wj * lever_j) rounds the partner's product
  // first, and from j's side the other one.
  GS_HD GS_INLINE bool particle_kinematics(Index i, Index j, const Vec3d& xi, ContactKinematics<Real>& k) const {
    return particle_kinematics(i, j, xi, Partner{position[j], radius[j]}, k);
  }
  // Where the partner's position and radius were loaded beforehand (add_list_contacts).
  struct Partner {
    Vec3d position;
    float radius;
  };
  GS_HD GS_INLINE bool particle_kinematics(Index i, Index j, const Vec3d& xi, const Partner& pj,
                                           ContactKinematics<Real>& k) const {
    const Vec3d d = box.separation(xi, pj.position);  // to the nearest image on the axes that wrap
    const double reach = double(radius[i]) + double(pj.radius);
    const double distance2 = norm2(d);
    if (distance2 >= reach * reach) return false;
    const double distance = std::sqrt(distance2);
    k.overlap = Real(reach - distance);
    k.normal = Vec3<Real>(d) * (Real(1) / Real(distance));  // a unit vector needs no more than force precision
    const Real ri = radius[i], rj = pj.radius;
    const Real lever_i = ri - Real(0.5) * k.overlap, lever_j = rj - Real(0.5) * k.overlap;
    const Vec3<Real> wi = spin(i), wj = spin(j);
    k.velocity = Vec3<Real>(velocity[i] - velocity[j]) - cross(add_rounded(wi * lever_i, wj * lever_j), k.normal);
    k.angular_velocity = wi - wj;
    const Real mi = mass[i], mj = mass[j];
    k.effective_mass = mi * mj / (mi + mj);
    k.effective_radius = ri * rj / (ri + rj);
    k.lever = lever_i;
    k.partner_lever = lever_j;
    return true;
  }

  // A sphere's angular velocity. Without friction or rolling resistance
  // nothing turns a sphere and no force depends on its spin (the normal force
  // sees only the normal component of the contact point's velocity, to which
  // a spin adds none), so the kernel reads none: it is zero here, and a run
  // keeps the field only where a particle starts spinning (its output).
  GS_HD GS_INLINE Vec3<Real> spin(Index i) const {
    if constexpr (kTorque) {
      return Vec3<Real>(angular_velocity[i]);
    } else {
      return Vec3<Real>();
    }
  }

  // Particle i against a rigid surface (an analytic wall or a mesh feature)
  // whose material moves at surface_velocity at the contact point and turns
  // at surface_angular_velocity: the surface acts as a partner of infinite
  // mass and radius.
  GS_HD ContactKinematics<Real> surface_kinematics(Index i, double overlap, const Vec3d& normal,
                                                   const Vec3d& surface_velocity,
                                                   const Vec3d& surface_angular_velocity) const {
    ContactKinematics<Real> k;
    k.overlap = Real(overlap);
    k.normal = Vec3<Real>(normal);
    const Real ri = radius[i];
    k.lever = ri - k.overlap;
    const Vec3<Real> wi = spin(i);
    k.velocity = Vec3<Real>(velocity[i] - surface_velocity) - cross(wi * k.lever, k.normal);
    k.angular_velocity = wi - Vec3<Real>(surface_angular_velocity);
    k.effective_mass = mass[i];
    k.effective_radius = ri;
    return k;
  }

 private:
  // Visitor of the cells' candidates: one possible partner j of particle i
  // (a Verlet list's go through add_list_contacts).
  struct ParticleVisitor {
    const ForceKernel* kernel;
    Index i;
    Vec3d xi;
    ContactLoad<Real>* total;
    int* pairs_touching;
    // Candidates without list entries (cells) have nowhere to keep springs.
    GS_HD GS_INLINE void operator()(Index j) const {
      static_assert(!kHistory, "contact history needs the Verlet list's entries");
      if (j != i) kernel->add_particle_contact(i, j, ListOffset(0), xi, *total);
    }
  };

  // Releases the surface slots no contact touched, checks the row, writes the sums.
  GS_HD GS_INLINE void finish(Index i, const ContactLoad<Real>& total, unsigned touched, int pairs_touching) const {
    if constexpr (kHistory) {
      surface_history.release_untouched(i, touched);
      // A row of contact_slots must hold them all when the particle migrates or is checkpointed.
      if (pairs_touching + bit_count(touched) > contact_slots) report_fault(fault, kFaultSlotsExhausted, id[i], step);
    }
    force[i] = total.force;
    if constexpr (kTorque) torque[i] = total.torque;
  }

  // total += load, each sum rounded on its own (core/vec3.hpp: add_rounded).
  GS_HD GS_INLINE static void add_to(ContactLoad<Real>& total, const ContactLoad<Real>& load) {
    total.force = add_rounded(total.force, load.force);
    if constexpr (kTorque) total.torque = add_rounded(total.torque, load.torque);
  }

#if defined(__CUDACC__)
  // Lane `lane`'s load, on every lane of the group.
  template <class Group>
  __device__ static ContactLoad<Real> shuffled(const Group& g, const ContactLoad<Real>& v, int lane) {
    ContactLoad<Real> r;
    r.force = g.shuffle(v.force, lane);
    if constexpr (kTorque) r.torque = g.shuffle(v.torque, lane);
    return r;
  }
#endif

  // Visitor of for_each_mesh_contact: one mesh contact of particle i. A
  // contact whose feature already has a history slot is applied at once; a
  // new one waits until every such contact has marked its slot touched, so
  // that it can take over only the slot of a contact that has ended (the
  // same contact, moved on to an adjacent feature).
  struct MeshContactVisitor {
    const ForceKernel* kernel;
    Index i;
    Vec3d xi;
    ContactLoad<Real>* total;
    unsigned* touched;
    MeshContact* waiting;
    int* n_waiting;
    GS_HD void operator()(const MeshContact& c) const {
      if constexpr (kHistory) {
        const int slot = kernel->surface_history.find(i, mesh_partner_id(c.feature_key));
        if (slot < 0 && *n_waiting < kWaitingMeshContacts) {
          waiting[(*n_waiting)++] = c;
          return;
        }
        kernel->add_mesh_contact(i, xi, c, slot < 0 ? kAnySlot : slot, *total, *touched);
      } else {
        kernel->add_mesh_contact(i, xi, c, kAnySlot, *total, *touched);
      }
    }
  };

  GS_HD void add_mesh_contacts(Index i, const Vec3d& xi, ContactLoad<Real>& total, unsigned& touched) const {
    clear_mesh_load(i);
    MeshContact waiting[kWaitingMeshContacts];
    int n_waiting = 0;
    MeshContactVisitor visit{this, i, xi, &total, &touched, waiting, &n_waiting};
    const ListOffset first = mesh_near.begin[i];
    const std::int32_t count = std::int32_t(mesh_near.begin[i + 1] - first);
    for_each_near_mesh_contact(meshes, mesh_near.triangles + first, count, xi, double(radius[i]), visit);
    add_waiting_mesh_contacts(i, xi, waiting, n_waiting, total, touched);
  }

  GS_HD GS_INLINE void clear_mesh_load(Index i) const {
    if (mesh_load)
      for (int m = 0; m < meshes.n_meshes; ++m) mesh_load[std::size_t(i) * meshes.n_meshes + m] = MeshLoad{};
  }

  // The mesh contacts that found no slot of their own, once the others have taken theirs.
  GS_HD void add_waiting_mesh_contacts(Index i, const Vec3d& xi, const MeshContact* waiting, int n_waiting,
                                       ContactLoad<Real>& total, unsigned& touched) const {
    for (int k = 0; k < n_waiting; ++k) {
      const MeshContact& c = waiting[k];
      const int slot = surface_history.inherit(i, mesh_partner_id(c.feature_key), touched, SameMeshContact{&meshes, c.feature_key});
      add_mesh_contact(i, xi, c, slot < 0 ? kAnySlot : slot, total, touched);
    }
  }

  // As a wall contact, at the mesh feature's contact point; the load on the
  // mesh is the reaction: minus the force, and minus the moment about the
  // mesh's rotation centre c of the force at the particle centre plus the
  // torque about it ((x_i - c) x F + T, which includes the rolling couple).
  GS_HD void add_mesh_contact(Index i, const Vec3d& xi, const MeshContact& c, int slot, ContactLoad<Real>& total,
                              unsigned& touched) const {
    const MeshPose& pose = meshes.pose[c.mesh];
    const ContactKinematics<Real> k =
        surface_kinematics(i, c.overlap, c.normal, c.wall_velocity, pose.angular_velocity);
    const ContactLoad<Real> load = apply(i, mesh_partner_id(c.feature_key),
                                         pairs(material[i], meshes.material[c.mesh]), k, total, touched, slot);
    if (mesh_load) {
      MeshLoad& on_mesh = mesh_load[std::size_t(i) * meshes.n_meshes + c.mesh];
      const Vec3d f(load.force);
      Vec3d moment = cross(xi - (pose.axis_point + pose.shift), f);
      if constexpr (kTorque) moment += Vec3d(load.torque);
      on_mesh.force -= f;
      on_mesh.torque -= moment;
    }
  }

  // The pair (i, j) of i's list entry k and j's entry r (which names i),
  // for both spheres: the law once, j's load and springs mirrored. Inlined
  // into pairs_of: as a call (GCC's choice for a function this long) the
  // CPU's dense bed stepped 4-9 % slower (docs/PERFORMANCE.md, "Orientation
  // only where the snapshots hold it, and two calls inlined").
  GS_HD GS_INLINE void pair_once(Index i, Index j, ListOffset k, ListOffset r, const Vec3d& xi,
                                 const EntryLoads<Real>& e) const {
    ContactKinematics<Real> c;
    if (!particle_kinematics(i, j, xi, c)) {
      e.touching[k] = e.touching[r] = 0;
      if constexpr (kHistory) {
        pair_history.release(k);
        pair_history.release(r);
      }
      return;
    }
    ContactState<Real> state;
    if constexpr (kHistory) state = pair_history.load(k);
    const ContactForces<Real> f = contact_forces<Real, Model, Effects>(pairs(material[i], material[j]), c, state, dt);
    if constexpr (kHistory) {
      pair_history.store(k, state);
      pair_history.store(r, mirrored(state));
    }
    e.load[k] = load_on<Real, Effects>(f, c.normal, c.lever);
    e.load[r] = load_on<Real, Effects>(mirrored(f), -c.normal, c.partner_lever);
    e.touching[k] = e.touching[r] = 1;
  }

  // The pair (i, j) of list entry `entry`: its springs are that entry's. 1
  // where they touch; else the entry is released (the contact has ended).
  GS_HD GS_INLINE int add_particle_contact(Index i, Index j, ListOffset entry, const Vec3d& xi,
                                           ContactLoad<Real>& total) const {
    return add_particle_contact(i, j, entry, xi, Partner{position[j], radius[j]}, total);
  }
  GS_HD GS_INLINE int add_particle_contact(Index i, Index j, ListOffset entry, const Vec3d& xi, const Partner& pj,
                                           ContactLoad<Real>& total) const {
    ContactLoad<Real> load;
    if (!particle_contact(i, j, entry, xi, pj, load)) return 0;
    add_to(total, load);
    return 1;
  }

  // The pairs of i's Verlet list entries, in list order, added to total;
  // returns how many touch. The partner of the next entry, its position and
  // radius, is loaded before this entry's contact is computed: a thread's
  // gathers by partner id are what the kernel waits on (docs/PERFORMANCE.md,
  // the force kernel's roofline), and the compiler does not move a load of
  // entry k + 1 above the stores of entry k's springs by itself.
  GS_HD GS_INLINE int add_list_contacts(Index i, const Vec3d& xi, ContactLoad<Real>& total) const {
    const ListOffset end = candidates.begin[i + 1];
    ListOffset k = candidates.begin[i];
    if (k == end) return 0;
    int touching = 0;
    Index j = candidates.list[k];
    Partner pj{position[j], radius[j]};
    for (; k + 1 < end; ++k) {
      const Index next = candidates.list[k + 1];
      const Partner ahead{position[next], radius[next]};
      if (j != i) touching += add_particle_contact(i, j, k, xi, pj, total);
      j = next;
      pj = ahead;
    }
    if (j != i) touching += add_particle_contact(i, j, k, xi, pj, total);
    return touching;
  }

  // The load of the pair (i, j) of list entry `entry` on i, and true, where
  // they touch; else false, and the entry's springs are released.
  GS_HD GS_INLINE bool particle_contact(Index i, Index j, ListOffset entry, const Vec3d& xi,
                                        ContactLoad<Real>& load) const {
    return particle_contact(i, j, entry, xi, Partner{position[j], radius[j]}, load);
  }
  GS_HD GS_INLINE bool particle_contact(Index i, Index j, ListOffset entry, const Vec3d& xi, const Partner& pj,
                                        ContactLoad<Real>& load) const {
    ContactKinematics<Real> k;
    if (!particle_kinematics(i, j, xi, pj, k)) {
      if constexpr (kHistory) pair_history.release(entry);
      return false;
    }
    ContactState<Real> state;
    if constexpr (kHistory) state = pair_history.load(entry);
    load = contact_load<Real, Model, Effects>(pairs(material[i], material[j]), k, state, dt);
    if constexpr (kHistory) pair_history.store(entry, state);
    return true;
  }

  // The walls in scene order, each behind its cheap first test.
  GS_HD GS_INLINE void add_wall_contacts(Index i, const Vec3d& xi, ContactLoad<Real>& total, unsigned& touched) const {
    const double ri = radius[i];
    for (int w = 0; w < n_walls; ++w)
      if (wall_may_touch(wall_screens[w], xi, ri)) add_wall_contact(i, w, xi, total, touched);
  }

  GS_HD void add_wall_contact(Index i, int w, const Vec3d& xi, ContactLoad<Real>& total, unsigned& touched) const {
    WallContact wc;
    if (!wall_contact(walls[w], xi, double(radius[i]), wc)) return;
    const ContactKinematics<Real> k =
        surface_kinematics(i, wc.overlap, wc.normal, wc.wall_velocity, walls[w].angular_velocity);
    apply(i, kWallPartnerBase + ParticleId(w), pairs(material[i], walls[w].material), k, total, touched);
  }

  // slot: the contact's history slot when the caller knows it, else kAnySlot.
  GS_HD GS_INLINE ContactLoad<Real> apply(Index i, ParticleId partner_id, const PairParams<Real, Model>& p,
                                const ContactKinematics<Real>& k, ContactLoad<Real>& total, unsigned& touched,
                                int slot = kAnySlot) const {
    ContactState<Real> state;
    if constexpr (kHistory) {
      if (slot == kAnySlot) slot = surface_history.find_or_claim(i, partner_id, touched);
      if (slot >= 0) {
        touched |= 1u << slot;
        state = surface_history.load(i, slot);
      } else {
        report_fault(fault, slot == kNoRowSlot ? kFaultSurfaceUnforeseen : kFaultSurfaceSlotsExhausted, id[i], step);
      }
    }
    const ContactLoad<Real> load = contact_load<Real, Model, Effects>(p, k, state, dt);
    if constexpr (kHistory) {
      if (slot >= 0) surface_history.store(i, slot, state);
    }
    add_to(total, load);
    return load;
  }
};

// A ForceKernel of one thread per particle for a scene without meshes, whose
// path it compiles out: on a GPU that path, taken by no thread there, cost
// the frictional kernel registers, a stack frame and spills
// (docs/PERFORMANCE.md, "A force kernel without the mesh path").
template <class K>
struct WithoutMeshes {
  static constexpr int kMinBlocksPerSM = K::kMinBlocksPerSM;
  K k;
  GS_HD GS_INLINE void operator()(Index i) const { k.template contacts<false>(i); }
};

}  // namespace gs
