#pragma once
// Insertion of particles during a run, through the scene's inlets
// (docs/SCENES.md `inlets`, docs/DESIGN.md "Insertion"). Every rank computes
// the same batch: which particles an inlet owes, their sizes and velocities,
// and the candidate positions of each, all drawn from a counter-based random
// generator keyed by (seed, inlet, particle index, batch), so nothing depends
// on the rank count or on what came before a restart. Each rank then marks
// the candidates that overlap its own particles; the marks are summed over
// the ranks; and every rank accepts the same candidates in the same order.
#include <cstdint>
#include <vector>

#include "core/insertion_state.hpp"
#include "core/materials.hpp"
#include "core/periodic_box.hpp"
#include "scene/inlet_spec.hpp"
#include "walls/mesh.hpp"
#include "walls/wall.hpp"

namespace gs {

// The particles one inlet owes at one batch, and where each may go: the same
// on every rank.
struct InletBatch {
  std::vector<ParticleInit> pending;  // in sequence order; id and position unset
  std::vector<float> mass;            // stored mass of each [kg]
  int attempts = 0;
  std::vector<Vec3d> candidates;      // pending.size() * attempts centres, particle by particle
};

// The inlet's state before any batch; the run's next id follows the scene's particles.
InsertionState initial_insertion_state(std::size_t inlets, std::size_t scene_particles);

// Whether `step` is one of the inlet's batch steps (a multiple of its interval).
bool batch_due(const InletSpec& inlet, long long step);

// What inlet number `which` owes at time t (its rate or total since `start`,
// less what it has inserted), with the candidates of batch `state.batches`.
InletBatch inlet_batch(const InletSpec& inlet, std::size_t which, const InletState& state, double t,
                       const std::vector<MaterialSpec>& materials);

// Adds 1 to blocked[c] for each candidate c that overlaps one of the spheres
// (centre, radius) or, on the axes of `box` that wrap, one of their periodic
// images (a sphere just across a periodic face touches the candidates near
// the other face): this rank's share of the marks.
void mark_blocked(const InletBatch& batch, const std::vector<Vec3d>& centre, const std::vector<float>& radius,
                  const PeriodicBox& box, std::vector<double>& blocked);

// The accepted particles of the batch, in sequence order: each pending
// particle takes its first candidate that no rank marked and that overlaps no
// wall, no mesh and no particle accepted before it in this batch. Stops at
// the first particle without such a candidate (the rest stay owed). No
// periodic images are needed here: a batch's spheres lie wholly inside the
// region, which lies inside the domain, so two of them never meet through a
// periodic face (an existing particle may straddle one: mark_blocked).
// `meshes` must hold their vertices in the current pose.
std::vector<ParticleInit> accept_candidates(const InletBatch& batch, const std::vector<double>& blocked,
                                            const std::vector<Wall>& walls, const MeshSet& meshes);

}  // namespace gs
