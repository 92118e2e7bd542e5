#pragma once
// The per-step work of one rank. The force computation is compiled per
// backend, force precision, contact model and set of effects; the other
// parts per backend and force precision. make_step_kernels picks the ones a
// scene needs, so effects a scene does not use cost neither arithmetic nor
// memory.
#include <memory>
#include <vector>

#include "core/fault.hpp"
#include "core/materials.hpp"
#include "engine/force_computation.hpp"
#include "engine/integration.hpp"
#include "engine/neighbour_search.hpp"
#include "engine/particle_movement.hpp"
#include "engine/particle_removal.hpp"
#include "scene/scene.hpp"

namespace gs {

// Wall time per phase [s].
struct StepTimings {
  double integrate = 0, neighbours = 0, forces = 0, exchange = 0;
};

// The parts of one rank's step for one run, built together: each part is one
// concern (engine/particle_movement.hpp, neighbour_search.hpp,
// force_computation.hpp, integration.hpp) and they share the forces, the
// contact history and the fault flag (engine/step_state.hpp). comm/ sees the
// movement part only.
class StepKernels {
 public:
  virtual ~StepKernels() = default;

  virtual ParticleMovement& movement() = 0;
  virtual const ParticleMovement& movement() const = 0;
  virtual NeighbourSearch& neighbours() = 0;
  virtual ForceComputation& forces() = 0;
  virtual const ForceComputation& forces() const = 0;
  virtual Integration& integration() = 0;
  virtual ParticleRemoval& removal() = 0;  // particles that reached an exit (engine/particle_removal.hpp)

  // Sets the marker of each owned particle by its side of the plane.
  virtual void mark_by_plane(ParticleStore& s, const MarkingSpec& m) = 0;
  virtual Fault take_fault() = 0;  // the first fault since the last call, which clears it
  virtual void synchronize() const = 0;
  virtual std::size_t bytes() const = 0;  // every part's memory
};

struct KernelChoice {
  Backend backend;
  Precision precision;
  ContactModel model;
  unsigned effects;
};

// The kernels of `choice` for the scene's materials and pairs (the pair table
// in force precision is built from them by the chosen contact model).
struct ContactInputs {
  const std::vector<MaterialSpec>& materials;
  const std::vector<PairSpec>& pairs;
  int contact_slots;      // a particle's row of contacts (messages, checkpoints)
  int surface_slots = 4;  // its slots for walls and mesh features (scene key surface_slots)
  bool surface_row_for_every_particle = false;  // RunOptions' check (engine/surface_rows.hpp)
};
std::unique_ptr<StepKernels> make_step_kernels(const KernelChoice& choice, const ContactInputs& contacts);
std::unique_ptr<StepKernels> make_step_kernels_cpu(const KernelChoice& choice, const ContactInputs& contacts);
std::unique_ptr<StepKernels> make_step_kernels_cuda(const KernelChoice& choice, const ContactInputs& contacts);

}  // namespace gs
