#pragma once
// One (point, trial) work item of a single-scan run: draw the scenario from the item's own
// stream, run the reference (the first that solves, when the experiment names fallbacks) and
// every algorithm on that same draw, and format their rows of trials.csv (n_targets,
// n_measurements, max_error, mean_error against the reference's marginals, time_us,
// iterations, converged, w_star).
#include <memory>
#include <string>
#include <vector>

#include "harness/run/execution.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/single_scan/scenario.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

// One thread's solvers and buffers, reused for every item it runs.
struct SingleScanWorker final : RunWorker {
  std::vector<std::unique_ptr<SingleScanSolver>> solvers;
  std::vector<MarginalTable> marginals;
  std::vector<SolveReport> reports;
  std::vector<double> time_us;
  ScenarioSample sample;
};

class SingleScanExecution final : public RunExecution {
 public:
  SingleScanExecution(const RunPlan& plan, std::vector<std::unique_ptr<SingleScanScenario>> scenarios);
  std::unique_ptr<RunWorker> make_worker() const override;
  void run_unit(RunWorker& worker, long long item, std::size_t part) const override;
  void run_item(SingleScanWorker& worker, long long item) const;

 private:
  const RunPlan& plan_;
  std::vector<std::unique_ptr<SingleScanScenario>> scenarios_;
  std::vector<std::string> point_prefix_;  // "point,param values" per point
  std::vector<std::string> spec_field_;    // CSV-quoted SPEC per algorithm
};

}  // namespace dabench
