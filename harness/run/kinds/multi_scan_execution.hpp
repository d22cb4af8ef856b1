#pragma once
// One (point, trial) work item of a multi-scan run: draw the scenario from the item's own
// stream, run every multi-scan algorithm on that same draw, and format its rows of trials.csv
// (one per algorithm: n_targets, n_scans, n_measurements, mean_hpd, max_hpd, mean_entropy,
// time_us, iterations, converged, line_search_steps, residual, inner_residual — the last three
// empty for methods that do not report them) and targets.csv (one per algorithm and target: hpd, entropy;
// empty when the algorithm did not solve). Metrics are against the scenario's truth
// (harness/multi_scan/particle_metrics.hpp). A draw without targets is skipped:no_targets for every
// algorithm (there is nothing to associate or measure).
#include <memory>
#include <string>
#include <vector>

#include "harness/multi_scan/scenario.hpp"
#include "harness/multi_scan/solver.hpp"
#include "harness/run/execution.hpp"
#include "harness/run/run_plan.hpp"

namespace dabench {

struct MultiScanWorker final : RunWorker {
  std::vector<std::unique_ptr<MultiScanSolver>> solvers;
  std::vector<MultiScanBeliefs> beliefs;
  std::vector<SolveReport> reports;
  std::vector<double> time_us;
  MultiScanSample sample;
};

class MultiScanExecution final : public RunExecution {
 public:
  MultiScanExecution(const RunPlan& plan, std::vector<std::unique_ptr<MultiScanScenario>> scenarios);
  std::unique_ptr<RunWorker> make_worker() const override;
  void run_unit(RunWorker& worker, long long item, std::size_t part) const override;
  // Runs algorithms [first_algorithm, end_algorithm) of the plan on the item's draw: their rows.
  void run_item(MultiScanWorker& worker, long long item, std::size_t first_algorithm, std::size_t end_algorithm) const;

 private:
  const RunPlan& plan_;
  std::vector<std::unique_ptr<MultiScanScenario>> scenarios_;
  std::vector<std::string> point_prefix_;  // "point,param values" per point
  std::vector<std::string> spec_field_;    // CSV-quoted SPEC per algorithm
};

}  // namespace dabench
