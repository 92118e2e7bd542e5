#pragma once
// One rank's simulation: the particle store, the compiled step kernels for the
// scene's effects, walls and the time loop (velocity Verlet).
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/rank_exchange.hpp"
#include "engine/step_kernels.hpp"
#include "scene/scene.hpp"

namespace gs {

// A run stopped by a physical or numerical fault: names step, particle, cause.
struct SimulationFault : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Owned particles on the host, sorted by id.
struct ParticleSnapshot {
  double time = 0;
  long long step = 0;
  std::vector<ParticleId> id;
  std::vector<std::uint8_t> material, marker;
  std::vector<float> radius, mass, inertia;
  std::vector<Vec3d> position, velocity, angular_velocity, force, torque;
  std::vector<Quaternion> orientation;
  std::size_t size() const { return id.size(); }
};

struct RunOptions {
  Backend backend = Backend::cpu;
  int reorder_interval = 25;     // steps between re-sorting particle memory by cell
  int fault_check_interval = 50; // steps between reading the fault flag
  int rebalance_interval = 500;  // steps between load-balance checks (several ranks)
};

class Simulation {
 public:
  // `exchange`: null for a single rank; otherwise this rank keeps the scene's
  // particles it owns and trades the others with its neighbours every step.
  Simulation(const SceneSpec& scene, const RunOptions& options, std::shared_ptr<RankExchange> exchange = nullptr);

  void run(long long steps);  // advances `steps` time steps
  double time() const { return time_; }
  long long step_count() const { return step_; }
  const SceneSpec& scene() const { return scene_; }
  Backend backend() const { return options_.backend; }
  Index particle_count() const { return store_.n_owned; }  // owned by this rank
  const RankExchange* exchange() const { return exchange_.get(); }

  ParticleSnapshot snapshot() const;  // this rank's owned particles
  HostHistory history() const;  // in snapshot (id) order
  std::size_t device_bytes() const;
  const StepTimings& timings() const { return timings_; }

 private:
  void upload(const std::vector<ParticleInit>& particles);
  void move_walls(double t);
  void rebuild_cells();
  void step_particles_between_ranks();
  void check_fault();

  SceneSpec scene_;
  RunOptions options_;
  ParticleStore store_;
  std::unique_ptr<StepKernels> kernels_;
  std::shared_ptr<RankExchange> exchange_;
  CellGrid grid_;
  std::vector<Wall> walls_;
  bool walls_move_ = false;
  double time_ = 0;
  long long step_ = 0;
  StepTimings timings_;
};

}  // namespace gs
