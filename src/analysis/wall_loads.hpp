#pragma once
// Force and torque that the particles put on each analytic wall, for the time
// series. Evaluated on the host from a (gathered) snapshot and its contact
// history (of the particles with a stored wall contact: `on_walls`, sorted by
// id, as Simulation::wall_contact_history gives), with the same contact law
// as the force kernel: springs as stored, no spring increment (dt = 0), and the velocities of the snapshot (end of
// the step, half a step later than the force kernel saw them, which only
// touches the damping term). Summed in blocks of particles in id order, the
// blocks in order: the same bits whatever the threads (which share the
// blocks) or the ranks (the snapshot is gathered in id order).
#include <vector>

#include "core/particle_snapshot.hpp"
#include "scene/scene.hpp"
#include "walls/mesh.hpp"

namespace gs {

// One load per wall of `walls` (posed at the snapshot's time); torque about
// the wall's current rotation centre (axis_point + shift).
std::vector<MeshLoad> wall_loads(const SceneSpec& scene, const std::vector<Wall>& walls, const ParticleSnapshot& s,
                                 const ParticleRecords& on_walls);

}  // namespace gs
