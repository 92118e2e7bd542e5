#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <utility>

#include "contact/contact_time.hpp"
#include "contact/contact_models.hpp"
#include "core/id_order.hpp"
#include "core/wall_clock.hpp"
#include "engine/insertion.hpp"
#include "engine/particle_init.hpp"
#include "scene/particle_sources.hpp"
#include "scene/position_resolution.hpp"
#include "walls/wall_motion.hpp"

namespace gs {
namespace {

// The scene without its particles: once a rank's own are in the store, a
// second copy of the scene's (all of them, on every rank) would be dead weight.
SceneSpec without_particles(const SceneSpec& scene) {
  SceneSpec settings;
  static_cast<SceneSettings&>(settings) = scene;
  return settings;
}

// The first n ids of the store (its owned particles), in ascending id order.
std::vector<std::size_t> owned_id_order(const DeviceArray<ParticleId>& ids, std::size_t n) {
  std::vector<ParticleId> id(n);
  if (n > 0) backend_copy_to_host(ids.backend(), id.data(), ids.data(), n * sizeof(ParticleId));
  return id_order(id);
}

}  // namespace

Simulation::Simulation(const SceneSpec& scene, const RunOptions& options, std::shared_ptr<RankExchange> exchange)
    : scene_(without_particles(scene)), options_(options), exchange_(std::move(exchange)) {
  set_up(scene);
  insertion_ = initial_insertion_state(scene.inlets.size(), gs::particle_count(scene));
  move_walls(0.0);
  pose_meshes(0.0);
  // Each rank generates only the particles it owns (lattices site by site).
  const auto t0 = Clock::now();
  RankExchange* split = exchange_.get();
  std::function<bool(const Vec3d&)> keep;  // empty: every particle (one rank)
  KeepWindow window{Vec3d(-INFINITY, -INFINITY, -INFINITY), Vec3d(INFINITY, INFINITY, INFINITY)};
  if (split) {
    keep = [split](const Vec3d& x) { return split->owns(x); };
    split->owned_bounds(window.lo, window.hi);  // random-fill blocks elsewhere are never made
  }
  upload(scene, keep, window);
  if (exchange_) exchange_->refresh_ghosts(store_, kernels_->movement());
  kernels_->synchronize();
  setup_timings_.particles = seconds_since(t0);
  // Forces at t = 0 for the first half kick.
  const auto t1 = Clock::now();
  rebuild_neighbours();
  kernels_->forces().compute(store_, 0.0, 0);
  kernels_->synchronize();
  setup_timings_.first_forces = seconds_since(t1);
}

Simulation::Simulation(const SceneSpec& scene, const RunOptions& options, std::shared_ptr<RankExchange> exchange,
                       const RestartState& restart)
    : scene_(without_particles(scene)), options_(options), exchange_(std::move(exchange)) {
  set_up(scene);
  insertion_ = restart.insertion ? *restart.insertion : initial_insertion_state(scene.inlets.size(), gs::particle_count(scene));
  std::vector<Vec3d> force, torque;  // the owned particles' last forces, in store order
  restore(restart, force, torque);
  if (exchange_) exchange_->refresh_ghosts(store_, kernels_->movement());
  rebuild_neighbours();
  kernels_->movement().set_forces(store_, force, torque);
}

void Simulation::set_up(const SceneSpec& scene) {
  if (const std::string problem = fp32_state_problem(scene); !problem.empty()) throw std::invalid_argument(problem);
  // A negative skin would make cells narrower than a contact's reach.
  if (!(scene.verlet_skin >= 0) || !std::isfinite(scene.verlet_skin))
    throw std::invalid_argument("Verlet skin must be a finite number >= 0 (in largest diameters), got " +
                                std::to_string(scene.verlet_skin));
  const Backend b = options_.backend;
  store_.place_on(b);
  store_.fields_kept = particle_fields_kept(scene);
  kernels_ = make_step_kernels({b, scene.precision, scene.model, scene.effects},
                               {scene.materials, scene.pairs, scene.contact_slots, scene.surface_slots,
                                options_.surface_row_for_every_particle});
  const double diameter = 2.0 * largest_radius(scene), skin = scene.verlet_skin * diameter;
  skin_ = kernels_->neighbours().uses_verlet_list() ? skin : 0.0;
  grid_ = make_cell_grid(scene.domain_min, scene.domain_max, diameter + skin_, periodic_box(scene));
  // The halo's skin, with or without a Verlet list: ghosts then need
  // selecting only when a particle has moved half of it, which the
  // kick-drift's verdict on the list tells (it watches half of the narrower
  // of this and the list's skin).
  kernels_->neighbours().watch_moves(exchange_ ? exchange_->set_skin(skin) : skin_);
  walls_ = scene.walls;
  removes_ = scene.has_exits();
  if (removes_)
    kernels_->removal().set_exits(exits_of(scene.outlets, scene.open_faces), scene.domain_min, scene.domain_max);
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const Wall& w = walls_[k];
    walls_move_ = walls_move_ || norm2(w.velocity) > 0 || norm2(w.angular_velocity) > 0 ||
                  !timeline_of(scene.wall_timelines, k).none();
  }
  watch_walls_ = walls_move_ && history_fields_kept(scene.model, scene.effects) != 0;
  if (watch_walls_) {
    // A particle's centre stays within the domain (a cell's width beyond it
    // covers the step that finds one outside).
    const Vec3d margin{grid_.cell_size, grid_.cell_size, grid_.cell_size};
    wall_drift_ = WallDrift(scene.domain_min - margin, scene.domain_max + margin);
  }
  meshes_ = scene.meshes;
  if (meshes_.n_triangles() > 0) {
    if (meshes_.n_triangles() >= kMaxMeshFeatures || meshes_.n_vertices() >= kMaxMeshFeatures ||
        meshes_.n_edges >= kMaxMeshFeatures)
      throw std::runtime_error("the scene's meshes have more than 2^28 triangles, edges or vertices");
    for (const MeshMotion& m : meshes_.motion)
      meshes_move_ = meshes_move_ || norm2(m.velocity) > 0 || norm2(m.angular_velocity) > 0 || !m.timeline.none();
    kernels_->forces().set_meshes(meshes_);
    mesh_drift_ = MeshDrift(meshes_);
    // Bins in each mesh's own frame: binned once, whatever the motion.
    kernels_->forces().set_mesh_bins(bin_triangles(meshes_, grid_.cell_size, run_binning(grid_.cell_size, skin_)));
  }
}

// This rank's share of the saved particles, bit for bit, with their history,
// and their last forces into `force` and `torque` (store order: the caller
// sets them once the first list is built); walls are posed from the absolute
// time, as in the run.
void Simulation::restore(const RestartState& r, std::vector<Vec3d>& force, std::vector<Vec3d>& torque) {
  step_ = r.step;
  last_reorder_ = r.step;
  time_ = r.time;
  move_walls(time_);
  pose_meshes(time_);
  std::vector<Index> mine;
  for (std::size_t i = 0; i < r.particles.size(); ++i)
    if (!exchange_ || exchange_->owns(r.particles.position[i])) mine.push_back(Index(i));
  ParticleRecords part;
  const HostHistory& h = r.particles.history;
  const std::size_t slots = std::size_t(h.slots);
  part.history.slots = h.slots;
  auto take_rows = [&](const auto& from, auto& to, std::size_t i) {
    for (std::size_t s = 0; s < slots && !from.empty(); ++s) to.push_back(from[i * slots + s]);
  };
  // A checkpoint of a run that did not keep an optional field (image
  // counts, orientations) starts it here, as for a new particle.
  for (Index k : mine) {
    const std::size_t i = std::size_t(k);
    for_each_kept_particle_field(part, r.particles, store_.fields_kept, [i](const char*, auto& to, const auto& from) {
      to.push_back(from.empty() ? start_value<typename std::decay_t<decltype(from)>::value_type>() : from[i]);
    });
    force.push_back(r.force[i]);
    torque.push_back(r.torque[i]);
    take_rows(h.partner, part.history.partner, i);
    for_each_history_field(part.history, h, [&](const char*, unsigned, auto& to, const auto& from) {
      take_rows(from, to, i);
    });
  }
  store_.n_owned = 0;
  store_.n_ghost = 0;
  kernels_->movement().append(store_, part, false);
}

// The owned particles go straight from the generators into host copies of
// the store's fields (filled on every thread, no list of particles between),
// a block at a time, each uploaded to its place before the next is made: the
// host holds one block, not the rank's particles.
void Simulation::upload(const SceneSpec& scene, const std::function<bool(const Vec3d&)>& keep,
                        const KeepWindow& window) {
  constexpr std::size_t kBlock = std::size_t(1) << 22;
  ParticleRecords host;
  const bool fp32 = fp32_state(scene_.precision);  // positions and velocities start on the fp32 grid they live on
  for_each_selected_block(
      scene, keep, window, kBlock,
      [&](std::size_t n) {
        store_.resize_arrays(n);
        store_.n_owned = Index(n);
        const std::size_t held = std::min(n, kBlock);
        // Only the fields the run keeps: the others stay empty (set_particle leaves them be).
        for_each_kept_particle_field(host, store_.fields_kept,
                                     [held](const char*, auto& field) { field.resize(held); });
      },
      [&](std::size_t k, const ParticleInit& p) { set_particle(host, k, p, scene_.materials, fp32); },
      [&](std::size_t first, std::size_t count) {
        for_each_kept_particle_field(store_, host, store_.fields_kept,
                                     [first, count](const char*, auto& field, const auto& from) {
                                       field.from_host(from.data(), count, first);
                                     });
      });
  store_.n_ghost = 0;
  ++store_.revision;
  kernels_->movement().reserve(store_.n_owned);
}

void Simulation::move_walls(double t) {
  for (std::size_t k = 0; k < walls_.size(); ++k)
    walls_[k] = wall_at(scene_.walls[k], timeline_of(scene_.wall_timelines, k), t);
  kernels_->forces().set_walls(walls_);
}

// Poses from the absolute time; the backend poses its vertices from them.
void Simulation::pose_meshes(double t) {
  if (meshes_.n_triangles() == 0) return;
  set_mesh_poses(meshes_, t);
  kernels_->forces().set_mesh_pose(meshes_);
}

MeshSet Simulation::meshes() const {
  MeshSet posed = meshes_;
  move_meshes(posed, time_);
  return posed;
}

std::vector<MeshLoad> Simulation::mesh_loads() const {
  std::vector<MeshLoad> total(std::size_t(meshes_.n_meshes()));
  if (meshes_.n_triangles() == 0) return total;
  kernels_->synchronize();
  const std::vector<MeshLoad> per_particle = kernels_->forces().particle_mesh_loads(store_);
  const std::size_t k = total.size();
  const std::vector<std::size_t> order = owned_id_order(store_.id, std::size_t(store_.n_owned));
  for (std::size_t i : order)
    for (std::size_t m = 0; m < k; ++m) {
      total[m].force += per_particle[i * k + m].force;
      total[m].torque += per_particle[i * k + m].torque;
    }
  return total;
}

// Every build comes where no force on the backend is needed: in a step after
// its kick-drift has read the last forces and before its force pass writes
// every owned particle's anew; at the start before the first force pass, or,
// on a restart, while the saved forces wait on the host. So the force
// arrays' storage goes back to the backend while the build's transients are
// held (with a contact history the kept contacts beside the list's tables: a
// frictional run's peak), 24 bytes per particle in fp32.
void Simulation::rebuild_neighbours() {
  kernels_->movement().release_forces();
  try {
    kernels_->neighbours().build(store_, grid_, skin_);
    kernels_->forces().build_surface_lists(store_, skin_);
  } catch (...) {  // sized again, so that what reads them after the error reads no freed storage
    kernels_->movement().reserve(store_.size());
    throw;
  }
  kernels_->movement().reserve(store_.size());
  mesh_drift_.built(meshes_);
  if (watch_walls_) wall_drift_.built(walls_);
}

// The meshes' and walls' motion since the lists were built, against the half
// skin the near lists and the surface rows leave it (walls/mesh_near.hpp,
// engine/surface_rows.hpp); the same on every rank.
bool Simulation::surfaces_drifted() const {
  return (meshes_move_ && mesh_drift_.beyond(meshes_, 0.5 * skin_)) ||
         (watch_walls_ && wall_drift_.beyond(walls_, 0.5 * skin_));
}

IntegrationParams Simulation::integration_params() const {
  return {scene_.time_step, scene_.gravity, scene_.domain_min, scene_.domain_max, 0.5 * grid_.cell_size, step_,
          fp32_state(scene_.precision), scene_.open_faces, periodic_box(scene_)};
}

// The closing half kick of a step reads the forces that the next step's
// opening half kick reads too, so inside run() it waits for that step's
// kick-drift, which applies both (KickDrift::closing_kick): one pass over the
// velocities instead of two, the same bits. Nothing between the two reads the
// velocities but insertion, which finishes the kick first; run() finishes it
// before it returns or throws, so that no caller sees a half-kicked state.
void Simulation::finish_closing_kick() {
  if (!std::exchange(closing_kick_due_, false)) return;
  const auto t0 = Clock::now();
  kernels_->integration().kick(store_, integration_params());
  timings_.integrate += phase_seconds(t0);
}

void Simulation::run(long long steps, const std::function<bool()>& stop_after_step) {
  const auto start = Clock::now();
  const double dt = scene_.time_step;
  IntegrationParams p = integration_params();
  for (long long s = 0; s < steps; ++s) {
    // A timed step starts with an idle device, so it is charged only its own work.
    if (step_ % kTimedEvery == 0) kernels_->synchronize();
    if (exchange_) exchange_->time_phases(step_ % kTimedEvery == 0);
    auto t0 = Clock::now();
    p.step = step_ + 1;
    kernels_->integration().kick_drift(store_, p, std::exchange(closing_kick_due_, false));
    if (walls_move_) move_walls(time_ + dt);
    if (meshes_move_) pose_meshes(time_ + dt);
    // Removed where the drift took them, before they can migrate or touch anything.
    if (removes_) kernels_->removal().remove(store_, p.step, removed_);
    timings_.integrate += phase_seconds(t0);
    if (exchange_) exchange_particles();

    // A Verlet list is kept while it covers every contact: by the verdict
    // of the last step's kick-drift (no wait for the device; a list kept for
    // a step it did not cover is a fault, found a step later). With ranks
    // the halo's vote has already taken this rank's verdict and every
    // other's: a rebuild of the halo changed the store, and so the list is
    // rebuilt after it. Memory is re-sorted only at a rebuild.
    t0 = Clock::now();
    const bool build = kernels_->neighbours().stale(store_) || surfaces_drifted();
    timings_.neighbours += phase_seconds(t0);
    if (build) {
      finish_forward();  // (a list built on the ghosts' last positions would be wrong)
      time_rare(rare_timings_.neighbours, [this] {
        if (!exchange_) reorder_if_due();
        rebuild_neighbours();
      });
      ++neighbour_builds_;
    }

    compute_forces(dt, p.step);
    closing_kick_due_ = true;
    ++step_;
    time_ = double(step_) * dt;
    if (!scene_.inlets.empty()) insert_due();
    if (options_.fault_check_interval > 0 && step_ % options_.fault_check_interval == 0) check_fault();
    if (stop_after_step && stop_after_step()) break;
  }
  finish_closing_kick();
  check_fault();
  run_seconds_ += seconds_since(start);
}

StepTimings Simulation::timings() const {
  const StepTimings& r = rare_timings_;
  const double rare = r.integrate + r.neighbours + r.forces + r.exchange;
  const double sampled = timings_.integrate + timings_.neighbours + timings_.forces + timings_.exchange;
  const double scale = sampled > 0 ? std::max(0.0, run_seconds_ - rare) / sampled : 0.0;
  return {r.integrate + timings_.integrate * scale, r.neighbours + timings_.neighbours * scale,
          r.forces + timings_.forces * scale, r.exchange + timings_.exchange * scale};
}

void Simulation::time_rare(double& total, const std::function<void()>& work) {
  kernels_->synchronize();
  const auto t0 = Clock::now();
  work();
  kernels_->synchronize();
  total += seconds_since(t0);
}

// Kernels run asynchronously on a GPU: a phase ends when its kernels have.
// Waiting for them at every phase would keep the GPU idle while the host
// launches the next one, so only every kTimedEvery-th step is timed; it gives
// the split of run()'s measured time over the phases (timings()).
double Simulation::phase_seconds(std::chrono::steady_clock::time_point start) const {
  if (step_ % kTimedEvery != 0) return 0;
  kernels_->synchronize();
  return seconds_since(start);
}

// The halo as LAMMPS keeps it: rebuilt (migration or a load-balance check,
// then the ghosts selected anew within the interaction range plus the skin)
// only when some rank needs it, else the ghosts' positions and velocities
// forwarded over the recorded send lists, particles staying where they are
// (started here, finished by compute_forces).
void Simulation::exchange_particles() {
  auto t0 = Clock::now();
  const long long next = step_ + 1;
  const bool balance = options_.rebalance_interval > 0 && next % options_.rebalance_interval == 0;
  // This rank's moves: the verdict of the last step's kick-drift (no wait
  // for the device, as on one rank; neighbor/verlet_list.hpp, ListWatch).
  const bool due = balance || rebuild_due_ || surfaces_drifted() || kernels_->neighbours().stale(store_);
  if (!exchange_->halo_stale(store_, kernels_->movement(), due)) {
    exchange_->start_forward(store_, kernels_->movement());
    forward_in_flight_ = true;  // finished by compute_forces
    timings_.exchange += phase_seconds(t0);
    return;
  }
  timings_.exchange += phase_seconds(t0);  // the vote
  rebuild_due_ = false;
  time_rare(rare_timings_.exchange, [this, balance] {
    ParticleMovement& movement = kernels_->movement();
    if (!(balance && exchange_->rebalance(store_, movement))) exchange_->migrate(store_, movement);
  });
  time_rare(rare_timings_.neighbours, [this] { reorder_if_due(); });
  time_rare(rare_timings_.exchange, [this] { exchange_->refresh_ghosts(store_, kernels_->movement()); });
}

// The step's forces. While the ghosts' forward is in flight, the interior
// particles' first (their lists name no ghost), then, once the ghosts hold
// their new fields, the boundary's: each particle's force is the one a single
// pass gives, so the split changes no bit. A rank works on the interior while
// the messages travel, where it would have waited for them: the host, on a
// GPU, in the transport's wait while the device runs the interior's kernel.
// Timed steps (phase_seconds) wait for the device between the phases, and so
// overlap little.
void Simulation::compute_forces(double dt, long long step) {
  auto t0 = Clock::now();
  ForceComputation& forces = kernels_->forces();
  const GhostSplit split = kernels_->neighbours().ghost_split();
  if (forward_in_flight_ && split.valid()) {
    forces.compute_interior(store_, dt, step, split);
    timings_.forces += phase_seconds(t0);
    finish_forward();
    t0 = Clock::now();
    forces.compute_boundary(store_, dt, step, split);
  } else {
    finish_forward();  // a rank without ghosts still takes part
    t0 = Clock::now();
    forces.compute(store_, dt, step);
  }
  if (step == contact_measure_step_) measure_contacts();
  timings_.forces += phase_seconds(t0);
}

void Simulation::finish_forward() {
  if (!forward_in_flight_) return;
  const auto t0 = Clock::now();
  forward_in_flight_ = false;
  exchange_->finish_forward(store_, kernels_->movement());
  timings_.exchange += phase_seconds(t0);
}

// Every reorder_interval steps at most, the owned particles (no ghosts) are
// re-sorted in memory by cell.
void Simulation::reorder_if_due() {
  if (options_.reorder_interval <= 0 || step_ + 1 - last_reorder_ < options_.reorder_interval) return;
  store_.drop_ghosts();
  kernels_->neighbours().build_cell_list(store_, grid_);
  kernels_->movement().reorder(store_, kernels_->neighbours().cell_order());
  last_reorder_ = step_ + 1;
}

void Simulation::check_fault() {
  const Fault f = kernels_->take_fault();
  std::string message;
  if (f.code != kFaultNone)
    message = "step " + std::to_string(f.step) + ": particle " + std::to_string(f.particle) + ": " + fault_cause(f.code);
  if (exchange_) message = exchange_->first_fault(message);
  if (message.empty()) return;
  finish_closing_kick();  // what is written after a fault is a whole step
  throw SimulationFault(message);
}

ParticleSnapshot Simulation::snapshot() const {
  ParticleSnapshot s;
  HostPins unpinned(false);
  snapshot_into(s, unpinned);
  return s;
}

// Once the step's kernels are done: the owned particles' order by id, made
// on the backend (engine/owned_id_order.hpp), which every copy of fields in
// id order follows: where the owned ids are dense, a scatter by id that
// holds no order array beside the run; else the order array, in `storage`.
RowOrder Simulation::owned_row_order_on_backend(DeviceArray<Index>& storage) const {
  kernels_->synchronize();
  return kernels_->movement().owned_row_order(store_, storage);
}

void Simulation::snapshot_into(ParticleSnapshot& s, HostPins& pins, bool with_forces) const {
  DeviceArray<Index> storage(store_.backend);
  const RowOrder order = owned_row_order_on_backend(storage);
  s.time = time_;
  s.step = step_;
  kernels_->movement().owned_to_host(store_, order, s, pins, with_forces);
}

void Simulation::measure_contacts_at(long long step) {
  contact_measure_step_ = step;
  if (step == step_) measure_contacts();
}

void Simulation::measure_contacts() {
  const auto t0 = Clock::now();
  kernels_->forces().measure_contacts(store_, contact_measure_step_);
  kernels_->synchronize();  // only at the steps a measurement is due
  contact_pass_seconds_ += seconds_since(t0);
  measured_step_ = contact_measure_step_;
}

std::vector<ContactMeasure> Simulation::contact_measures() const {
  if (measured_step_ != step_)
    throw std::logic_error("no contact pass at step " + std::to_string(step_) + " (measure_contacts_at before the run)");
  kernels_->synchronize();
  const std::vector<ContactMeasure> m = kernels_->forces().contact_measures(store_);
  return permuted(m, owned_id_order(store_.id, m.size()));
}

ParticleRecords Simulation::wall_contact_history() const {
  ParticleRecords r;
  HostPins unpinned(false);
  wall_contact_history_into(r, unpinned);
  return r;
}

void Simulation::wall_contact_history_into(ParticleRecords& r, HostPins& pins) const {
  kernels_->synchronize();
  kernels_->movement().wall_contact_history(store_, r, pins);
}

HostHistory Simulation::history() const {
  HostHistory h;
  HostPins unpinned(false);
  history_into(h, unpinned);
  return h;
}

void Simulation::history_into(HostHistory& h, HostPins& pins) const {
  DeviceArray<Index> storage(store_.backend);
  const RowOrder order = owned_row_order_on_backend(storage);
  kernels_->movement().history_to_host(store_, order, h, pins);
}

std::size_t Simulation::device_bytes() const {
  return store_.bytes() + kernels_->bytes();
}

}  // namespace gs
