#pragma once
// One (point, trial) work item of a tracking run (jdt-vb-multipath-othr, Sec. IV): draw the
// scenario run from the item's own stream, run every tracker on that same draw (each call
// timed on the steady clock: TET), score it against the truth (harness/tracking/metrics.hpp)
// and format its rows of
//  - trials.csv: one per tracker, the metric columns of kinds/tracking.cpp: nvt, tpd,
//    nft, false_tracks, ghost_tracks, broken_targets, ttl_scans, aee_range_km,
//    aee_bearing_mrad, mospa_km (empty unless the tracker ran), tet_s (seconds), iterations,
//    converged, free_energy (from the SolveReport, empty unless the tracker ran; free_energy
//    also empty while the tracker leaves it NaN);
//  - tracks.csv: the truth first (algorithm `truth`, track = target number 1.., confirmed 1,
//    the scans where the target is alive, variances empty), then per tracker that ran, per
//    track in its order, per scan of the track: g, g_dot, theta, theta_dot and the covariance
//    diagonal var_* (rows 0..3 of the state: [g, ġ, ϑ, ϑ̇], the layout the metrics assume);
//  - iterations.csv (only with the experiment's `iterations = true`): each tracker's
//    record_iterations() history is collected during its call and, when the tracker's status
//    is ok, scored like its final tracks: one row per recorded track set r = 0, 1, ... with
//    the point's prefix, trial, seed, algorithm, iteration r, the metric columns nvt ..
//    mospa_km of trials.csv and free_energy (the set's TrackSet::objective, empty when NaN:
//    jdt-vb's B after iteration r). A tracker that records nothing (or did not run) has no rows; a
//    recorded set that does not fit the run marks the tracker failed:iteration r: <why>.
//    Recording happens inside the timed call, so with the switch on tet_s includes it (one
//    copy of the track set per iteration, small beside an iteration's work);
//  - measurements.csv: trial 0 of each point only (Fig. 5 needs one run; all 100 runs would
//    take ~100 MB per point at N_c = 400): per scan, per measurement in the scan's order, r,
//    r_dot, azimuth and its origin (target number 1.., path τ 1.. as in Table II; −1 and −1
//    for clutter).
// Scans are 0-based. Before each call the tracker's report is reset and its track set
// cleared; the tracker object is reused for every item of its thread. A tracker that throws
// gets status failed:<what()>, one that sets report.skipped gets skipped:<reason>, and one
// whose tracks do not fit the run (state rows below 4, covariance shape differing from the
// states, scans outside 0..K−1) gets failed:<why>; the other trackers and items go on. Line
// breaks in reasons become spaces. A draw without truth targets is scored against a target
// that is never alive, which changes no metric (NVT 0, TPD/TTL/AEE empty, NFT and MOSPA count
// the tracks).
#include <memory>
#include <string>
#include <vector>

#include "harness/run/execution.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/tracking/metrics.hpp"
#include "harness/tracking/scenario.hpp"
#include "harness/tracking/tracker.hpp"

namespace dabench {

struct TrackingWorker final : RunWorker {
  std::vector<std::unique_ptr<Tracker>> trackers;
  std::vector<TrackSet> tracks;
  std::vector<SolveReport> reports;
  std::vector<TrackingMetrics> metrics;
  std::vector<double> tet_s;
  std::vector<std::vector<TrackSet>> histories;                // per tracker, when recording
  std::vector<std::vector<TrackingMetrics>> iteration_metrics;  // per tracker, per recorded r
  TrackingScenarioSample sample;
};

class TrackingExecution final : public RunExecution {
 public:
  TrackingExecution(const RunPlan& plan, std::vector<std::unique_ptr<TrackingScenario>> scenarios,
                    const TrackingMetricsOptions& metrics);
  std::unique_ptr<RunWorker> make_worker() const override;
  void run_unit(RunWorker& worker, long long item, std::size_t part) const override;
  // Runs trackers [first_algorithm, end_algorithm) of the plan on the item's draw: their rows, and
  // with the first tracker the item's own rows (truth tracks, measurements).
  void run_item(TrackingWorker& worker, long long item, std::size_t first_algorithm, std::size_t end_algorithm) const;

 private:
  // Scores tracker a's recorded track sets into worker.iteration_metrics[a]; one that does not
  // fit the run marks the tracker failed:iteration r: <why>.
  void score_history(TrackingWorker& worker, std::size_t a, const TrackingTruth& scored, int scans) const;

  const RunPlan& plan_;
  std::vector<std::unique_ptr<TrackingScenario>> scenarios_;
  TrackingMetricsOptions metrics_;
  std::vector<std::string> point_prefix_;  // "point,param values" per point
  std::vector<std::string> spec_field_;    // CSV-quoted SPEC per tracker
  bool record_iterations_ = false;         // the experiment's `iterations = true`
};

// The metric options as a one-line JSON object, for meta.json (key "tracking_metrics").
std::string tracking_metrics_json(const TrackingMetricsOptions& options);

}  // namespace dabench
