#pragma once
// One (point, trial) work item of a track-before-detect run (tbd-bp-supplement): draw the run
// from the item's own stream, run every tracker on that same draw frame by frame (each step()
// timed on the steady clock), score each step (harness/tbd/metrics.hpp) and format its rows of
//  - trials.csv: one per tracker, the metric columns of kinds/tbd.cpp: n_steps, and the means
//    over the run's steps of gospa, gospa_p2, localisation, missed, false, n_objects, n_estimates
//    and step_time_us, then iterations (summed over steps) and converged (every step's);
//  - steps.csv: one per tracker and step k = 1..K (the paper's numbering): n_objects,
//    n_estimates, gospa, gospa_p2, localisation, missed, false, time_us — the curves over k of
//    the letter's Fig. 2 and the supplement's Figs 3-4 average these over trials;
//  - estimates.csv (trial 0 of each point only, for single-run figures): the truth first
//    (algorithm `truth`, label = object number 1.., existence 1), then each tracker's reports,
//    per step: k, label, existence, x, y, vx, vy;
//  - frames.csv (trial 0 only): per step, per cell: k, column, row, z1, z2;
//  - beliefs.csv (trial 0 only, with the experiment's `beliefs = true`): each tracker's
//    beliefs after the last step (TbdTracker::beliefs): k, label, existence, x, y, weight.
// The tracker object is reused for every item of its thread; start() begins each run. A
// tracker that throws gets status failed:<what()> (its later steps are not run), one that
// sets report.skipped gets skipped:<reason>; its steps.csv rows and estimates are not written.
#include <memory>
#include <string>
#include <vector>

#include "harness/run/execution.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/tbd/metrics.hpp"
#include "harness/tbd/scenario.hpp"
#include "harness/tbd/tracker.hpp"

namespace dabench {

struct TbdWorker final : RunWorker {
  std::vector<std::unique_ptr<TbdTracker>> trackers;
  std::vector<SolveReport> reports;
  std::vector<std::vector<TbdStepMetrics>> steps;               // per tracker, per step
  std::vector<std::vector<double>> step_seconds;                // per tracker, per step
  std::vector<std::vector<std::vector<TbdEstimate>>> reported;  // per tracker, per step (trial 0)
  std::vector<TbdEstimate> estimates;
  std::unique_ptr<TbdScorer> scorer;
  TbdSample sample;
  std::vector<TbdBeliefSample> belief_samples;
};

class TbdExecution final : public RunExecution {
 public:
  TbdExecution(const RunPlan& plan, std::vector<std::unique_ptr<TbdScenario>> scenarios,
               const TbdMetricsOptions& metrics);
  std::unique_ptr<RunWorker> make_worker() const override;
  void run_unit(RunWorker& worker, long long item, std::size_t part) const override;
  // Runs trackers [first_algorithm, end_algorithm) of the plan on the item's draw: their rows, and
  // with the first tracker the item's own rows (truth estimates, frames).
  void run_item(TbdWorker& worker, long long item, std::size_t first_algorithm, std::size_t end_algorithm) const;

 private:
  void run_tracker(TbdWorker& worker, std::size_t a, bool keep_estimates) const;

  const RunPlan& plan_;
  std::vector<std::unique_ptr<TbdScenario>> scenarios_;
  TbdMetricsOptions metrics_;
  std::vector<std::string> point_prefix_;  // "point,param values" per point
  std::vector<std::string> spec_field_;    // CSV-quoted SPEC per tracker
};

// The options as a one-line JSON object, for meta.json (key "tbd_metrics").
std::string tbd_metrics_json(const TbdMetricsOptions& options);

}  // namespace dabench
