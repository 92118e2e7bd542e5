#pragma once
// Flow of particles through a surface (a plane, a disk, a rectangle or a
// triangle mesh), counted from the particle centres at consecutive evaluations
// (docs/MEASUREMENTS.md): a particle has crossed when the straight segment
// between its two sampled centres cuts the plane inside the bound (a mesh:
// analysis/flow_mesh.hpp). Signed: +1 from the back (n . (x - point) < 0) to
// the front (>= 0), -1 back again.
// Evaluated on a gathered snapshot, in particle-id order: counts and mass sums
// are the same bits whatever the rank count.
#include <memory>
#include <string>
#include <vector>

#include "analysis/flow_mesh.hpp"
#include "core/particle_snapshot.hpp"
#include "scene/measurement_spec.hpp"

namespace gs {

// The crossing of one particle through a flat surface: +1, -1 or 0 (none, or
// outside the bound).
int flow_crossing(const FlowSpec& f, const Vec3d& before, const Vec3d& after);

// What crossed in one group of particles (a material, a marker, or all).
struct FlowTally {
  long long forward = 0, backward = 0;    // crossings in +normal and -normal direction
  double forward_mass = 0, backward_mass = 0;  // [kg]
  long long net_count() const { return forward - backward; }
  double net_mass() const { return forward_mass - backward_mass; }
  void add(const FlowCrossings& crossings, double mass);
};

// The rows of one evaluation: group 0 is every particle, then one per
// material, then one per marker of FlowSpec::markers.
struct FlowGroup {
  std::string material = "all", marker = "all";
  FlowTally interval, cumulative;
};

class FlowCounter {
 public:
  FlowCounter(const FlowSpec& spec, const std::vector<std::string>& material_names);

  const FlowSpec& spec() const { return spec_; }
  const std::vector<FlowGroup>& groups() const { return groups_; }
  double interval_seconds() const { return interval_; }
  // Counts the crossings since the last call (or since `start`) of the
  // particles present in both; `s` sorted by id (a gathered snapshot). The
  // first call only records the positions.
  void update(const ParticleSnapshot& s);
  // Positions to count from (after a restart: the checkpoint's) and the
  // cumulative totals of the log's last row, per group.
  void start(const ParticleSnapshot& s, const std::vector<FlowTally>& cumulative);

 private:
  void remember(const ParticleSnapshot& s);

  FlowCrossings crossings(const Vec3d& before, const Vec3d& after) const;

  FlowSpec spec_;
  std::shared_ptr<const FlowMeshSurface> mesh_;  // a mesh surface; null for a flat one
  std::vector<FlowGroup> groups_;
  std::vector<ParticleId> previous_id_;  // ascending
  std::vector<Vec3d> previous_position_;
  double previous_time_ = 0, interval_ = 0;
  bool started_ = false;
};

// The flow log (docs/OUTPUT.md): one row per group and evaluation.
const char* flow_csv_header();
std::vector<std::string> flow_csv_rows(const FlowCounter& counter, double time, long long step);
// The cumulative tallies of the log's rows of one evaluation, in the
// counter's group order (a group without a row: zero).
std::vector<FlowTally> flow_cumulative_from_rows(const FlowCounter& counter,
                                                 const std::vector<std::vector<std::string>>& rows);

}  // namespace gs
