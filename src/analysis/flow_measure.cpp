#include "analysis/flow_measure.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace gs {

int flow_crossing(const FlowSpec& f, const Vec3d& before, const Vec3d& after) {
  const double s0 = dot(before - f.point, f.normal), s1 = dot(after - f.point, f.normal);
  const bool front0 = s0 >= 0, front1 = s1 >= 0;
  if (front0 == front1) return 0;
  // Where the segment cuts the plane, relative to the plane's point.
  const Vec3d hit = before + (after - before) * (s0 / (s0 - s1)) - f.point;
  switch (f.bound) {
    case FlowBound::none:
    case FlowBound::mesh:  // counted by FlowMeshSurface
      break;
    case FlowBound::disk:
      if (norm2(hit - f.normal * dot(hit, f.normal)) > f.radius * f.radius) return 0;
      break;
    case FlowBound::rectangle:
      if (std::abs(dot(hit, f.axis_u)) > f.half_length_u || std::abs(dot(hit, f.axis_v)) > f.half_length_v) return 0;
      break;
  }
  return front1 ? 1 : -1;
}

void FlowTally::add(const FlowCrossings& crossings, double mass) {
  // A particle through a folded mesh may cross more than once; each crossing
  // adds its mass (in order, so that one crossing adds exactly `mass`).
  for (int k = 0; k < crossings.forward; ++k) {
    ++forward;
    forward_mass += mass;
  }
  for (int k = 0; k < crossings.backward; ++k) {
    ++backward;
    backward_mass += mass;
  }
}

FlowCounter::FlowCounter(const FlowSpec& spec, const std::vector<std::string>& material_names) : spec_(spec) {
  if (spec.bound == FlowBound::mesh) mesh_ = std::make_shared<const FlowMeshSurface>(spec.surface);
  groups_.emplace_back();
  for (const std::string& m : material_names) groups_.push_back({m, "all", {}, {}});
  for (int k : spec.markers) groups_.push_back({"all", std::to_string(k), {}, {}});
}

FlowCrossings FlowCounter::crossings(const Vec3d& before, const Vec3d& after) const {
  if (mesh_) return mesh_->crossings(before, after);
  const int c = flow_crossing(spec_, before, after);
  return {c > 0 ? 1 : 0, c < 0 ? 1 : 0};
}

void FlowCounter::remember(const ParticleSnapshot& s) {
  previous_id_ = s.id;
  previous_position_ = s.position;
  previous_time_ = s.time;
  started_ = true;
}

void FlowCounter::start(const ParticleSnapshot& s, const std::vector<FlowTally>& cumulative) {
  for (std::size_t g = 0; g < groups_.size() && g < cumulative.size(); ++g) groups_[g].cumulative = cumulative[g];
  remember(s);
}

void FlowCounter::update(const ParticleSnapshot& s) {
  for (FlowGroup& g : groups_) g.interval = FlowTally{};
  interval_ = started_ ? s.time - previous_time_ : 0;
  if (!started_) {
    remember(s);
    return;
  }
  const std::size_t n_materials = groups_.size() - 1 - spec_.markers.size();
  // Both lists ascend by id: one merge pass pairs each particle with its last position.
  std::size_t p = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    while (p < previous_id_.size() && previous_id_[p] < s.id[i]) ++p;
    if (p == previous_id_.size() || previous_id_[p] != s.id[i]) continue;
    const FlowCrossings c = crossings(previous_position_[p], s.position[i]);
    if (c.forward == 0 && c.backward == 0) continue;
    const double m = double(s.mass[i]);
    groups_[0].interval.add(c, m);
    if (std::size_t(s.material[i]) < n_materials) groups_[1 + s.material[i]].interval.add(c, m);
    for (std::size_t k = 0; k < spec_.markers.size(); ++k)
      if (int(s.marker[i]) == spec_.markers[k]) groups_[1 + n_materials + k].interval.add(c, m);
  }
  for (FlowGroup& g : groups_) {
    g.cumulative.forward += g.interval.forward;
    g.cumulative.backward += g.interval.backward;
    g.cumulative.forward_mass += g.interval.forward_mass;
    g.cumulative.backward_mass += g.interval.backward_mass;
  }
  remember(s);
}

namespace {

std::string exact(double x) {
  char s[32];
  std::snprintf(s, sizeof(s), "%.17g", x);
  return s;
}

}  // namespace

const char* flow_csv_header() {
  return "time,step,interval,material,marker,forward_count,backward_count,net_count,net_mass,count_rate,mass_rate,"
         "cumulative_forward_count,cumulative_backward_count,cumulative_forward_mass,cumulative_backward_mass,"
         "cumulative_net_count,cumulative_net_mass";
}

std::vector<std::string> flow_csv_rows(const FlowCounter& counter, double time, long long step) {
  std::vector<std::string> rows;
  const double dt = counter.interval_seconds();
  for (const FlowGroup& g : counter.groups()) {
    const FlowTally& i = g.interval;
    const FlowTally& c = g.cumulative;
    // No rate over the first evaluation, which only records the positions.
    const std::string count_rate = dt > 0 ? exact(double(i.net_count()) / dt) : "nan";
    const std::string mass_rate = dt > 0 ? exact(i.net_mass() / dt) : "nan";
    rows.push_back(exact(time) + "," + std::to_string(step) + "," + exact(dt) + "," + g.material + "," + g.marker +
                   "," + std::to_string(i.forward) + "," + std::to_string(i.backward) + "," +
                   std::to_string(i.net_count()) + "," + exact(i.net_mass()) + "," + count_rate + "," + mass_rate +
                   "," + std::to_string(c.forward) + "," + std::to_string(c.backward) + "," + exact(c.forward_mass) +
                   "," + exact(c.backward_mass) + "," + std::to_string(c.net_count()) + "," + exact(c.net_mass()));
  }
  return rows;
}

std::vector<FlowTally> flow_cumulative_from_rows(const FlowCounter& counter,
                                                 const std::vector<std::vector<std::string>>& rows) {
  std::vector<FlowTally> out(counter.groups().size());
  for (std::size_t g = 0; g < out.size(); ++g)
    for (const std::vector<std::string>& r : rows) {
      if (r.size() < 17 || r[3] != counter.groups()[g].material || r[4] != counter.groups()[g].marker) continue;
      out[g].forward = std::stoll(r[11]);
      out[g].backward = std::stoll(r[12]);
      out[g].forward_mass = std::stod(r[13]);
      out[g].backward_mass = std::stod(r[14]);
    }
  return out;
}

}  // namespace gs
