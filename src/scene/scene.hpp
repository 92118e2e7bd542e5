#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/inlet_spec.hpp"
#include "scene/measurement_spec.hpp"
#include "scene/mixing_spec.hpp"
#include "scene/outlets.hpp"
#include "scene/particle_sets.hpp"
#include "core/materials.hpp"
#include "core/particle_fields.hpp"
#include "core/periodic_box.hpp"
#include "core/types.hpp"
#include "core/vec3.hpp"
#include "io/snapshot_fields.hpp"
#include "walls/mesh.hpp"
#include "walls/timeline.hpp"
#include "walls/wall.hpp"

namespace gs {

class KeptFillBlocks;

// A bad scene: the message names the key and the line of the file.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct OutputSpec {
  double interval = 0;     // simulated seconds between snapshots; 0: final only
  std::string directory = "out";
  std::string format = "hdf5";           // hdf5 (with an XDMF index) or csv
  std::vector<std::string> fields;       // snapshot fields; empty: the default set (docs/OUTPUT.md)
  double checkpoint_interval = 0;        // simulated seconds between checkpoints; 0: none
  double checkpoint_minutes = 0;         // wall-clock minutes between checkpoints; 0: none
};

enum class DecompositionMethod { slabs, metis };

// How a run on several ranks splits space (ignored on one rank).
struct DecompositionSpec {
  DecompositionMethod method = DecompositionMethod::slabs;
  int axis = -1;                      // slabs: 0, 1, 2, or -1 for the longest loaded extent
  double rebalance_threshold = 1.2;   // re-partition when max/mean particles per rank exceeds this
};

// Sets every particle's marker by its side of a plane at one instant (the
// seed's procedure: settle, then mark by the side of the central vertical
// plane). Markers never change otherwise.
struct MarkingSpec {
  double time = 0;           // [s]
  Vec3d point, normal;       // the plane; normal of unit length
  std::uint8_t front = 1;    // marker where (x - point) . normal >= 0
  std::uint8_t back = 0;     // marker elsewhere
};

// The Verlet list's and the halo's skin where the scene does not set
// `verlet_skin`, in largest particle diameters.
constexpr double kDefaultVerletSkin = 0.1;

// Everything a scene sets but its particles.
struct SceneSettings {
  std::string path;                  // file it came from, for messages
  Vec3d domain_min, domain_max;      // particles must stay inside [m]
  unsigned periodic_axes = 0;        // bit a: axis a wraps (core/periodic_box.hpp)
  Vec3d gravity;                     // [m/s^2]
  ContactModel model = ContactModel::linear;
  Precision precision = Precision::fp32;
  unsigned effects = 0;              // set of Effect bits
  std::vector<MaterialSpec> materials;
  std::vector<PairSpec> pairs;       // every unordered pair of materials that can touch
  std::vector<Wall> walls;
  std::vector<std::string> wall_names;
  std::vector<Timeline> wall_timelines;  // one per wall, or none (walls/timeline.hpp)
  MeshSet meshes;                    // triangle-mesh walls (docs/MESHES.md); names in meshes.names
  double time_step = 0;              // resolved absolute time step [s]
  double contact_time = 0;           // shortest pair contact time [s]
  double stable_time_step = 0;       // largest stable step (contact/stable_step.hpp) [s]
  std::string stable_step_binding;   // the spring that sets it
  double duration = 0;               // simulated time [s]
  OutputSpec output;
  int contact_slots = 12;            // contacts a particle may have (its row in checkpoints and messages)
  int surface_slots = 4;             // of them, with walls and mesh features at once (history slots)
  double verlet_skin = kDefaultVerletSkin;  // Verlet list and halo skin, in largest particle diameters
  DecompositionSpec decomposition;
  std::optional<MixingSpec> mixing;  // analysis.mixing (docs/MIXING.md); none: no mixing analysis
  std::optional<MarkingSpec> marking;  // none: markers stay as created
  std::vector<OutletSpec> outlets;   // regions where particles are removed (scene/outlets.hpp)
  unsigned open_faces = 0;           // domain faces particles leave through, removed (scene/outlets.hpp)
  bool has_exits() const { return !outlets.empty() || open_faces != 0; }  // particles can leave the run
  std::vector<InletSpec> inlets;       // particles inserted during the run (engine/insertion.hpp)
  MeasurementsSpec measurements;     // flows and averages during the run (docs/MEASUREMENTS.md)
  bool frozen_particles = false;     // some particle set is `frozen` (a scene built in code sets it too)
  // "<file>:<line>: <key path>: <what>" for each value the scene sets that the
  // run ignores (a parameter of an effect that is off); check and run print them.
  std::vector<std::string> warnings;
};

// The domain's periodic box (no axis wraps when periodic_axes is 0).
inline PeriodicBox periodic_box(const SceneSettings& s) {
  return make_periodic_box(s.periodic_axes, s.domain_min, s.domain_max);
}
// Whether the run's snapshots hold orientations, which nothing else reads:
// only then does it keep and integrate them. (Names the loader or the run's
// output has checked: an unknown one throws, as there.)
inline bool snapshots_hold_orientations(const OutputSpec& o) {
  return !o.fields.empty() && parse_snapshot_fields(o.fields).has(SnapshotField::orientation);
}

struct SceneSpec : SceneSettings {
  // The initial particles, in kinds of sets whose ids interleave in the
  // file's order: particles given one by one (lists, scenes built in code),
  // ascending ids; and lattices and random fills, kept as their description
  // and generated where needed (scene/particle_sources.hpp), so that no rank
  // ever holds every particle of a big set.
  std::vector<ParticleInit> particles;
  std::vector<LatticeSource> lattices;
  std::vector<RandomFillSource> fills;
  std::vector<ParticleSetOrigin> set_origins;  // ascending `first`, one per set
  // Fill blocks made once and kept for a rank's later set-up passes
  // (scene/kept_fill_blocks.hpp); none kept when null.
  std::shared_ptr<KeptFillBlocks> kept_blocks;
};

// Whether a particle of the scene starts with a non-zero angular velocity: one
// given one by one, a lattice's, a random fill's or an inlet's (scene/particle_sources.cpp).
bool starts_spinning(const SceneSpec& s);

// The optional particle fields a run of the scene keeps (ParticleField bits).
inline unsigned particle_fields_kept(const SceneSpec& s) {
  const bool spins = makes_torques(s.effects) || starts_spinning(s);
  return (s.periodic_axes != 0 ? kImageCounts : 0u) | (s.frozen_particles ? kFrozenFlags : 0u) |
         (snapshots_hold_orientations(s.output) ? kOrientations : 0u) | (spins ? kAngularVelocities : 0u);
}

}  // namespace gs
