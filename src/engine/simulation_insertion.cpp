// Simulation::insert_due: the inlets' batches at a step (engine/insertion.hpp),
// and the data movement that puts the accepted particles into the store of
// the rank that owns their position.
#include "contact/contact_models.hpp"
#include "engine/insertion.hpp"
#include "engine/particle_init.hpp"
#include "engine/simulation.hpp"

namespace gs {
namespace {

// Host copies of the owned particles' centres and radii: what the overlap
// marks need of the store.
void owned_spheres(const ParticleStore& s, std::vector<Vec3d>& centre, std::vector<float>& radius) {
  const std::size_t n = std::size_t(s.n_owned);
  centre = s.position.to_host();
  radius = s.radius.to_host();
  centre.resize(n);
  radius.resize(n);
}

}  // namespace

// Collective with ranks: every rank runs every batch (the same candidates),
// so every rank reaches the same sums.
void Simulation::insert_due() {
  std::vector<ParticleInit> inserted;
  std::vector<Vec3d> centre;
  std::vector<float> radius;
  bool copied = false;
  MeshSet posed;  // the meshes' vertices in their pose now, once per step with a batch
  for (std::size_t i = 0; i < scene_.inlets.size(); ++i) {
    const InletSpec& in = scene_.inlets[i];
    if (!batch_due(in, step_)) continue;
    finish_closing_kick();  // the particles already there are seen at the whole step
    InletState& st = insertion_.inlets[i];
    InletBatch batch = inlet_batch(in, i, st, time_, scene_.materials);
    if (batch.pending.empty()) continue;
    // Checked where they will be stored: fp32 state keeps positions on the fp32 grid.
    if (fp32_state(scene_.precision))
      for (Vec3d& c : batch.candidates) c = on_fp32_grid(c);
    if (!copied) {
      owned_spheres(store_, centre, radius);
      if (meshes_.n_triangles() > 0) posed = meshes();
    }
    copied = true;
    std::vector<double> blocked;
    mark_blocked(batch, centre, radius, periodic_box(scene_), blocked);
    if (exchange_) exchange_->sum(blocked);
    const std::vector<ParticleInit> accepted = accept_candidates(batch, blocked, walls_, posed);
    // Every rank finds this alike, so all of them stop here together.
    if (insertion_.next_id + accepted.size() > std::uint64_t(kMaxParticleId) + 1)
      throw SimulationFault(in.key + " (inlet '" + in.name + "'): step " + std::to_string(step_) +
                            ": the run has used every particle id (32-bit ids are never reused)");
    InsertionRecord r{step_, time_, int(i), accepted.size(), 0.0, batch.pending.size() - accepted.size(), {}};
    for (std::size_t k = 0; k < accepted.size(); ++k) {
      ParticleInit p = accepted[k];
      p.id = ParticleId(insertion_.next_id++);
      r.mass += double(batch.mass[k]);
      st.mass += double(batch.mass[k]);
      inserted.push_back(p);
      // The next inlet's candidates must avoid these too: on every rank, as
      // any sphere of it counts once the marks are summed.
      centre.push_back(p.position);
      radius.push_back(float(p.radius));
    }
    st.inserted += accepted.size();
    ++st.batches;
    r.total = st;
    insertion_records_.push_back(r);
  }
  if (!inserted.empty()) append_inserted(inserted);
}

// The inserted particles this rank owns join its owned particles with no
// force (they touch nothing) and no contact history.
void Simulation::append_inserted(const std::vector<ParticleInit>& inserted) {
  std::vector<ParticleInit> mine;
  for (const ParticleInit& p : inserted)
    if (!exchange_ || exchange_->owns(p.position)) mine.push_back(p);
  ParticleRecords r;
  for_each_particle_field(r, [n = mine.size()](const char*, auto& field) { field.resize(n); });
  const bool fp32 = fp32_state(scene_.precision);
  for (std::size_t k = 0; k < mine.size(); ++k) set_particle(r, k, mine[k], scene_.materials, fp32);
  if (keeps_history(scene_.model, scene_.effects)) {
    const std::size_t rows = mine.size() * std::size_t(scene_.contact_slots);
    r.history.slots = scene_.contact_slots;
    r.history.partner.assign(rows, kNoPartner);
    for_each_history_field(r.history, [rows](const char*, unsigned, auto& field) { field.resize(rows); });
  }
  kernels_->synchronize();
  std::vector<Vec3d> force = kernels_->movement().forces(store_), torque = kernels_->movement().torques(store_);
  force.resize(force.size() + mine.size());
  torque.resize(torque.size() + mine.size());
  store_.drop_ghosts();
  kernels_->movement().append(store_, r, false);
  kernels_->movement().set_forces(store_, force, torque);
  // Ghosts are selected anew, after a migration, at the next step: owned
  // particles may lie up to half a skin outside their rank's region now,
  // and a halo selected from here would not last half a skin more.
  rebuild_due_ = true;
}

}  // namespace gs
