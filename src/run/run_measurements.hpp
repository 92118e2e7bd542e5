#pragma once
// The measurements of a run (scene key `measurements`, docs/MEASUREMENTS.md):
// their schedule, the contact pass they need, and their logs and grids.
// Collective: every rank calls each member; the evaluation runs on rank 0 on
// the gathered particles (in id order), which writes, and a failure to write
// stops every rank with the same RankFailure.
#include <memory>
#include <string>
#include <vector>

#include "analysis/flow_measure.hpp"
#include "comm/transport.hpp"
#include "engine/schedule.hpp"
#include "engine/simulation.hpp"
#include "io/csv_log.hpp"
#include "io/h5_grid.hpp"

namespace gs {

class RunMeasurements {
 public:
  RunMeasurements(const SceneSpec& scene, const std::string& directory, Transport& transport);

  // The first step after `step` at which a measurement is due; -1 when none is.
  long long next_due_after(long long step) const;
  // Before the run advances to `step`: asks for the contact pass there when
  // a coordination or stress average is due at it.
  void prepare(Simulation& sim, long long step) const;
  // Evaluates what is due at the simulation's step. At a checkpoint
  // (`checkpoint`) every flow that has started is evaluated too, so that a
  // restart from it continues from a sample and counts exactly.
  void evaluate(const Simulation& sim, bool checkpoint = false);
  // After a restart at the simulation's step, in its directory (whose logs
  // prepare_output_directory has cut at the step): the flows continue from
  // the restored positions and the cumulative totals of their last row, the
  // grid indexes list the earlier grids.
  void resume(const Simulation& sim);
  // What the measurements cost this rank so far, for the log: per
  // measurement its evaluations and host time, the gathers, the contact pass.
  std::string cost_summary(const Simulation& sim) const;

 private:
  struct Flow {
    Schedule schedule;
    FlowCounter counter;
    std::unique_ptr<CsvLog> log;
    long long last_step = -1;
    long long evaluations = 0;
    double seconds = 0;
  };
  struct Average {
    Schedule schedule;
    const AverageSpec* spec;
    std::unique_ptr<CsvLog> log;
    std::vector<GridSeriesEntry> grids;
    long long last_step = -1;
    long long evaluations = 0;
    double seconds = 0;
  };
  void write_average(Average& a, const ParticleSnapshot& s, const std::vector<ContactMeasure>& contacts);

  std::string directory_;
  Transport& transport_;
  std::vector<Flow> flows_;
  std::vector<Average> averages_;
  double gather_seconds_ = 0;
};

}  // namespace gs
