#pragma once
// One rank's simulation: the particle store, the compiled step kernels for the
// scene's effects, walls and the time loop (velocity Verlet).
#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "backend/host_pins.hpp"
#include "core/insertion_state.hpp"
#include "core/particle_snapshot.hpp"
#include "engine/rank_exchange.hpp"
#include "engine/step_kernels.hpp"
#include "scene/scene.hpp"
#include "walls/mesh_drift.hpp"
#include "walls/wall_drift.hpp"

namespace gs {

struct KeepWindow;  // scene/particle_sources.hpp

// A run stopped by a physical or numerical fault: names step, particle, cause.
struct SimulationFault : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  Backend backend = Backend::cpu;
  int reorder_interval = 25;     // steps between re-sorting particle memory by cell
  int fault_check_interval = 50; // steps between reading the fault flag
  int rebalance_interval = 500;  // steps between load-balance checks (several ranks)
  // A row of surface slots for every particle instead of those within reach
  // of a wall or mesh (engine/surface_rows.hpp): a check of the rule, which
  // must give the same bits.
  bool surface_row_for_every_particle = false;
};

class Simulation {
 public:
  // `exchange`: null for a single rank; otherwise this rank keeps the scene's
  // particles it owns and trades with its neighbours: every step the ghosts'
  // positions and velocities, and when the halo is rebuilt the particles.
  Simulation(const SceneSpec& scene, const RunOptions& options, std::shared_ptr<RankExchange> exchange = nullptr);
  // Continues from `restart` instead of the scene's initial particles.
  // Neither constructor throws on a fault in the first forces (too many
  // contacts): it is thrown by check_fault() or the first run(), once the
  // caller can save the state it was found in.
  Simulation(const SceneSpec& scene, const RunOptions& options, std::shared_ptr<RankExchange> exchange,
             const RestartState& restart);

  // Advances `steps` time steps, or fewer: `stop_after_step`, when given, is
  // called after every step and ends the run early by returning true (with
  // several ranks every rank calls it at every step, so it may communicate).
  void run(long long steps, const std::function<bool()>& stop_after_step = {});
  // Throws SimulationFault when a kernel has reported a fault since the last
  // check. Collective with several ranks (the fault of the lowest failing rank).
  void check_fault();
  // The particles this rank removed at the scene's exits since the last call,
  // in the order they were found (by step, then in store order).
  std::vector<RemovedParticle> take_removed() { return std::exchange(removed_, {}); }
  // Sets every owned particle's marker by its side of the plane, now.
  void mark(const MarkingSpec& m) { kernels_->mark_by_plane(store_, m); }
  double time() const { return time_; }
  long long step_count() const { return step_; }
  // The scene's settings; its particles are not kept (they are in the store).
  const SceneSpec& scene() const { return scene_; }
  Backend backend() const { return options_.backend; }
  Index particle_count() const { return store_.n_owned; }  // owned by this rank
  RankExchange* exchange() const { return exchange_.get(); }
  const std::vector<Wall>& walls() const { return walls_; }  // posed at time()
  MeshSet meshes() const;  // posed at time(), vertices included (for output)
  // Load of this rank's owned particles on each mesh (force, and torque about
  // the mesh's rotation centre), from the last force computation, summed in
  // particle id order (deterministic). With several ranks the caller sums
  // over ranks (RankExchange::sum): a total that is not bitwise independent
  // of the rank count, as any sum of doubles in a different grouping.
  std::vector<MeshLoad> mesh_loads() const;

  ParticleSnapshot snapshot() const;  // this rank's owned particles
  // The same into `s`, whose arrays keep their memory from call to call
  // (output reuses one set), page-locked by `pins` on a GPU; without the
  // forces and torques (left empty) where the caller reads neither.
  void snapshot_into(ParticleSnapshot& s, HostPins& pins, bool with_forces = true) const;
  // The measurements' contact pass (engine/contact_measure_kernel.hpp) at
  // `step`: after that step's force computation, or now when the simulation
  // is at it. Its result, per owned particle in snapshot (id) order
  // (std::logic_error unless the pass ran at the current step).
  void measure_contacts_at(long long step);
  std::vector<ContactMeasure> contact_measures() const;
  double contact_pass_seconds() const { return contact_pass_seconds_; }  // wall time of every pass so far
  HostHistory history() const;  // in snapshot (id) order
  void history_into(HostHistory& h, HostPins& pins) const;  // as snapshot_into
  // Ids (ascending) and history of the particles with a stored wall contact.
  ParticleRecords wall_contact_history() const;
  void wall_contact_history_into(ParticleRecords& r, HostPins& pins) const;  // as snapshot_into
  std::size_t device_bytes() const;
  // Wall time in run() per phase: the total is measured; the rare work (a
  // list build, the halo's rebuild, a re-sort) is timed each time it runs,
  // and what is left is split over the phases as the timed steps split it
  // (every kTimedEvery-th, see phase_seconds).
  StepTimings timings() const;
  // Builds of the neighbour structure in run() so far (a Verlet list's
  // rebuilds; every step without one).
  long long neighbour_builds() const { return neighbour_builds_; }
  // Wall time of the set-up of a new run (zero after a restart).
  struct SetupTimings {
    double particles = 0;     // generating and uploading the owned particles, the first ghosts
    double first_forces = 0;  // the first neighbour search and force computation
  };
  const SetupTimings& setup_timings() const { return setup_timings_; }
  // Where the inlets' insertion stands (checkpoints keep it), and the batches
  // inserted since the last call (simulation_insertion.cpp).
  const InsertionState& insertion() const { return insertion_; }
  std::vector<InsertionRecord> take_insertion_records() { return std::exchange(insertion_records_, {}); }

 private:
  void set_up(const SceneSpec& scene);
  void upload(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep, const KeepWindow& window);
  void restore(const RestartState& restart, std::vector<Vec3d>& force, std::vector<Vec3d>& torque);
  void move_walls(double t);
  void pose_meshes(double t);
  void rebuild_neighbours();  // where no force's value is needed on the backend: without the force arrays
  // A build of the lists is due for the meshes' or the walls' motion.
  bool surfaces_drifted() const;
  void insert_due();
  void append_inserted(const std::vector<ParticleInit>& inserted);
  void measure_contacts();  // the contact pass, now
  RowOrder owned_row_order_on_backend(DeviceArray<Index>& storage) const;  // (synchronises first)
  void exchange_particles();
  void compute_forces(double dt, long long step);
  void finish_forward();  // the ghosts' forward, where one is in flight
  IntegrationParams integration_params() const;
  // The step's closing half kick, where it was deferred to the next step's
  // kick-drift: before anything reads or changes the velocities outside a step.
  void finish_closing_kick();
  void reorder_if_due();
  double phase_seconds(std::chrono::steady_clock::time_point start) const;
  // Runs `work`, rare and waiting for the device anyway, between two waits
  // for the device, and adds its wall time to `total`: every time, so that
  // a list build or a halo rebuild counts whether or not a timed step has one.
  void time_rare(double& total, const std::function<void()>& work);
  // Steps between timed ones: each waits for the device five times.
  static constexpr long long kTimedEvery = 128;

  SceneSpec scene_;
  RunOptions options_;
  ParticleStore store_;
  std::unique_ptr<StepKernels> kernels_;
  std::shared_ptr<RankExchange> exchange_;
  CellGrid grid_;
  double skin_ = 0;  // Verlet list skin [m]; 0 without a list
  std::vector<Wall> walls_;
  bool walls_move_ = false;
  // Only the surface rows (engine/surface_rows.hpp) follow the walls' motion:
  // set where the run keeps contact history and a wall moves.
  bool watch_walls_ = false;
  WallDrift wall_drift_;
  MeshSet meshes_;
  bool meshes_move_ = false;
  MeshDrift mesh_drift_;
  double time_ = 0;
  long long step_ = 0;
  long long last_reorder_ = 0;  // step of the last memory re-sort
  long long neighbour_builds_ = 0;
  bool forward_in_flight_ = false;  // started by exchange_particles, finished by compute_forces
  // The last step's closing half kick is still to come (run(): the next
  // kick-drift applies it first, or finish_closing_kick).
  bool closing_kick_due_ = false;
  bool rebuild_due_ = false;  // the store changed (insertion): the halo is rebuilt at the next step
  long long contact_measure_step_ = -1;  // the step of the next contact pass; -1: none
  long long measured_step_ = -1;         // the step of the last one
  double contact_pass_seconds_ = 0;
  StepTimings timings_;  // sampled: the timed steps' phases, less their rare work
  StepTimings rare_timings_;  // measured: every rare work's (time_rare)
  double run_seconds_ = 0;  // all of run(), measured
  SetupTimings setup_timings_;
  bool removes_ = false;  // the scene has exits (outlets or open faces)
  std::vector<RemovedParticle> removed_;  // since the last take_removed()
  InsertionState insertion_;
  std::vector<InsertionRecord> insertion_records_;
};

}  // namespace gs
