#include "run/run_measurements.hpp"

#include <cstdio>
#include <filesystem>

#include "analysis/bin_average.hpp"
#include "comm/contact_measure_gather.hpp"
#include "comm/rank_agreement.hpp"
#include "comm/snapshot_gather.hpp"
#include "core/wall_clock.hpp"

namespace gs {
namespace {

std::string grid_file_name(const std::string& name, long long step) {
  char s[64];
  std::snprintf(s, sizeof(s), "_%010lld.h5", step);
  return "average_" + name + s;
}

std::vector<std::string> material_names(const SceneSpec& scene) {
  std::vector<std::string> names;
  for (const MaterialSpec& m : scene.materials) names.push_back(m.name);
  return names;
}

}  // namespace

RunMeasurements::RunMeasurements(const SceneSpec& scene, const std::string& directory, Transport& transport)
    : directory_(directory), transport_(transport) {
  const double dt = scene.time_step;
  for (const FlowSpec& f : scene.measurements.flows) {
    Flow flow{Schedule{f.times.start, f.times.every, dt}, FlowCounter(f, material_names(scene)), nullptr, -1};
    if (transport_.rank() == 0)
      flow.log = std::make_unique<CsvLog>(directory_ + "/flow_" + f.name + ".csv", flow_csv_header());
    flows_.push_back(std::move(flow));
  }
  for (const AverageSpec& a : scene.measurements.averages) {
    Average average{Schedule{a.times.start, a.times.every, dt}, &a, nullptr, {}, -1};
    if (transport_.rank() == 0)
      average.log = std::make_unique<CsvLog>(directory_ + "/average_" + a.name + ".csv", average_csv_header(a));
    averages_.push_back(std::move(average));
  }
}

long long RunMeasurements::next_due_after(long long step) const {
  long long next = -1;
  auto earliest = [&](const Schedule& s) {
    const long long k = s.next_after(step);
    if (next < 0 || k < next) next = k;
  };
  for (const Flow& f : flows_) earliest(f.schedule);
  for (const Average& a : averages_) earliest(a.schedule);
  return next;
}

void RunMeasurements::prepare(Simulation& sim, long long step) const {
  for (const Average& a : averages_)
    if (a.spec->needs_contacts() && a.schedule.due(step)) {
      sim.measure_contacts_at(step);
      return;
    }
}

void RunMeasurements::evaluate(const Simulation& sim, bool checkpoint) {
  const long long step = sim.step_count();
  std::vector<Flow*> flows;
  std::vector<Average*> averages;
  bool contacts_needed = false;
  for (Flow& f : flows_) {
    const bool started = step >= f.schedule.step_of(0);
    if (f.last_step != step && (f.schedule.due(step) || (checkpoint && started))) flows.push_back(&f);
  }
  for (Average& a : averages_)
    if (a.last_step != step && a.schedule.due(step)) {
      averages.push_back(&a);
      contacts_needed = contacts_needed || a.spec->needs_contacts();
    }
  if (flows.empty() && averages.empty()) return;
  const auto t0 = Clock::now();
  ParticleSnapshot local = sim.snapshot();
  std::vector<ContactMeasure> contacts;
  if (contacts_needed) contacts = gather_contact_measures(transport_, local.id, sim.contact_measures());
  const ParticleSnapshot s = gather_snapshot(transport_, std::move(local));
  gather_seconds_ += seconds_since(t0);
  written_by_rank_0(transport_, [&] {
    for (Flow* f : flows) {
      const auto t1 = Clock::now();
      f->counter.update(s);
      f->log->append(flow_csv_rows(f->counter, s.time, s.step));
      f->seconds += seconds_since(t1);
    }
    for (Average* a : averages) {
      const auto t1 = Clock::now();
      write_average(*a, s, contacts);
      a->seconds += seconds_since(t1);
    }
  });
  for (Flow* f : flows) {
    f->last_step = step;
    ++f->evaluations;
  }
  for (Average* a : averages) {
    a->last_step = step;
    ++a->evaluations;
  }
}

void RunMeasurements::write_average(Average& a, const ParticleSnapshot& s, const std::vector<ContactMeasure>& contacts) {
  const AverageSpec& spec = *a.spec;
  AverageSpec whole = spec;
  whole.bins = {1, 1, 1};
  a.log->append({average_csv_row(spec, bin_averages(whole, s, contacts)[0], s.time, s.step)});
  if (spec.bin_count() == 1) return;
  GridSeriesEntry e;
  e.time = s.time;
  e.step = s.step;
  e.h5_file = grid_file_name(spec.name, s.step);
  e.shape = average_grid_shape(spec);
  const std::vector<GridField> fields = average_grid_fields(spec, bin_averages(spec, s, contacts));
  for (const GridField& f : fields) e.fields.emplace_back(f.name, f.components);
  write_grid_h5(directory_ + "/" + e.h5_file, e.shape, fields, e.time, e.step);
  a.grids.push_back(e);
  write_grid_xdmf(directory_ + "/average_" + spec.name + ".xdmf", spec.name, a.grids);
}

std::string RunMeasurements::cost_summary(const Simulation& sim) const {
  if (flows_.empty() && averages_.empty()) return "";
  char line[200];
  std::string out;
  for (const Flow& f : flows_) {
    std::snprintf(line, sizeof(line), "measurement flow %s: %lld evaluations, %.3f s\n", f.counter.spec().name.c_str(),
                  f.evaluations, f.seconds);
    out += line;
  }
  for (const Average& a : averages_) {
    std::snprintf(line, sizeof(line), "measurement average %s: %lld evaluations, %.3f s\n", a.spec->name.c_str(),
                  a.evaluations, a.seconds);
    out += line;
  }
  std::snprintf(line, sizeof(line), "measurements: gathering %.3f s, contact pass %.3f s (in contact forces)\n",
                gather_seconds_, sim.contact_pass_seconds());
  return out + line;
}

void RunMeasurements::resume(const Simulation& sim) {
  const long long step = sim.step_count();
  if (flows_.empty() && averages_.empty()) return;
  const ParticleSnapshot s = flows_.empty() ? ParticleSnapshot() : gather_snapshot(transport_, sim.snapshot());
  written_by_rank_0(transport_, [&] {
    for (Flow& f : flows_) {
      const std::vector<std::vector<std::string>> last = f.log->last_rows();
      // A flow that had started continues from this state, which its last
      // evaluation (at the checkpoint) saw, and from the totals of the log's
      // row there (none in another run's directory: from zero).
      if (step >= f.schedule.step_of(0)) f.counter.start(s, flow_cumulative_from_rows(f.counter, last));
    }
    for (Average& a : averages_) {
      if (a.spec->bin_count() == 1) continue;
      for (long long k = 0; a.schedule.step_of(k) <= step; ++k) {
        const std::string name = grid_file_name(a.spec->name, a.schedule.step_of(k));
        if (std::filesystem::exists(directory_ + "/" + name)) a.grids.push_back(read_grid_entry(directory_, name));
      }
    }
  });
  for (Flow& f : flows_) f.last_step = step;
  for (Average& a : averages_) a.last_step = step;
}

}  // namespace gs
