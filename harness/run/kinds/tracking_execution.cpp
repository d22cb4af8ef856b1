#include "harness/core/special_values.hpp"
#include "harness/run/kinds/tracking_execution.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/row_fields.hpp"
#include "harness/run/trial_draw.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kStateColumns = 4;  // [g, ġ, ϑ, ϑ̇]
constexpr TrackingMetrics kMissing{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};

std::string failure(std::string_view what) { return "failed:" + one_line(what); }

// The metric columns shared by trials.csv and iterations.csv, nvt .. mospa_km.
void append_metrics(std::string& row, const TrackingMetrics& m) {
  for (const double value : {m.nvt, m.tpd, m.nft, m.false_tracks, m.ghost_tracks, m.broken_targets, m.ttl_scans,
                             m.aee_range_km, 1e3 * m.aee_bearing_rad, m.mospa_km}) {
    append_number(row, value);
  }
}

// Why `tracks` cannot be written or scored against a run of `scans` scans; "" if they can.
std::string tracks_error(const TrackSet& tracks, int scans) {
  for (const Track& track : tracks.tracks) {
    if (track.states.rows() < kStateColumns) {
      return fmt::format("track {} has {} state rows, expected at least {}", track.id, track.states.rows(), kStateColumns);
    }
    if (track.covariance_diagonals.rows() != track.states.rows() ||
        track.covariance_diagonals.cols() != track.states.cols()) {
      return fmt::format("track {} covariance diagonals are {}x{}, states {}x{}", track.id,
                         track.covariance_diagonals.rows(), track.covariance_diagonals.cols(), track.states.rows(),
                         track.states.cols());
    }
    if (track.first_scan < 0 || track.first_scan + track.length() > scans) {
      return fmt::format("track {} covers scans {}..{}, outside 0..{}", track.id, track.first_scan,
                         track.first_scan + track.length() - 1, scans - 1);
    }
  }
  return {};
}

// The truth to score against: the draw's, or for a draw without targets one target that is
// never alive (metrics need the scan count; such a target changes no metric).
const TrackingTruth& scoring_truth(const TrackingTruth& truth, int scans, TrackingTruth& never_alive) {
  if (!truth.targets.empty()) return truth;
  never_alive.targets.assign(1, {Eigen::MatrixXd::Constant(kStateColumns, scans, kNaN), std::vector<bool>(scans, false)});
  return never_alive;
}

}  // namespace

std::string tracking_metrics_json(const TrackingMetricsOptions& options) {
  return fmt::format(R"({{"min_track_length": {}, "gate_km": {}, "min_follow_fraction": {}, "ospa_cutoff_km": {}, )"
                     R"("ospa_order": {}, "aee_assigned": {}}})",
                     options.min_track_length, options.gate_km, options.min_follow_fraction, options.ospa_cutoff_km,
                     options.ospa_order, options.aee_assigned);
}

TrackingExecution::TrackingExecution(const RunPlan& plan, std::vector<std::unique_ptr<TrackingScenario>> scenarios,
                                     const TrackingMetricsOptions& metrics)
    : plan_(plan),
      scenarios_(std::move(scenarios)),
      metrics_(metrics),
      point_prefix_(plan.point_row_prefixes()),
      spec_field_(plan.spec_fields()),
      record_iterations_(plan.experiment.record_iterations) {
  if (const std::string why = metrics_.validate(); !why.empty()) throw InputError("[metrics]: " + why);
}

std::unique_ptr<RunWorker> TrackingExecution::make_worker() const {
  auto made = std::make_unique<TrackingWorker>();
  TrackingWorker& worker = *made;
  for (const std::string& spec : plan_.specs) worker.trackers.push_back(make_tracker(spec));
  worker.tracks.resize(plan_.specs.size());
  worker.reports.resize(plan_.specs.size());
  worker.metrics.resize(plan_.specs.size());
  worker.tet_s.resize(plan_.specs.size());
  if (record_iterations_) {
    worker.histories.resize(plan_.specs.size());
    worker.iteration_metrics.resize(plan_.specs.size());
  }
  worker.texts.resize(record_iterations_ ? 4 : 3);  // tracks, measurements, [iterations,] trials.csv
  return made;
}

void TrackingExecution::run_unit(RunWorker& worker, long long item, std::size_t part) const {
  run_item(static_cast<TrackingWorker&>(worker), item, part, part + 1);
}

void TrackingExecution::score_history(TrackingWorker& worker, std::size_t a, const TrackingTruth& scored,
                                      int scans) const {
  std::vector<TrackingMetrics>& out = worker.iteration_metrics[a];
  for (std::size_t r = 0; r < worker.histories[a].size(); ++r) {
    const TrackSet& tracks = worker.histories[a][r];
    std::string error = tracks_error(tracks, scans);
    if (error.empty()) {
      try {
        out.push_back(compute_tracking_metrics(scored, tracks, metrics_));
      } catch (const InputError& what) {
        error = what.what();
      }
    }
    if (!error.empty()) {  // a tracker bug: the whole run is marked, not only its history
      worker.reports[a].skipped = failure(fmt::format("iteration {}: {}", r, error));
      out.clear();
      return;
    }
  }
}

void TrackingExecution::run_item(TrackingWorker& worker, long long item, std::size_t first_algorithm,
                                 std::size_t end_algorithm) const {
  const auto start = Clock::now();
  const auto [point, trial] = draw_trial(plan_, scenarios_, item, worker.sample);
  const TrackingProblem& problem = worker.sample.problem;
  const TrackingTruth& truth = worker.sample.truth;
  const int scans = problem.scan_count();
  TrackingTruth never_alive;
  const TrackingTruth& scored = scoring_truth(truth, scans, never_alive);

  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
    SolveReport& report = worker.reports[a];
    TrackSet& tracks = worker.tracks[a];
    report.reset();
    tracks.tracks.clear();
    if (record_iterations_) {
      worker.histories[a].clear();
      worker.iteration_metrics[a].clear();
      worker.trackers[a]->record_iterations(&worker.histories[a]);
    }
    const auto t0 = Clock::now();
    try {
      worker.trackers[a]->run(problem, tracks, report);
    } catch (const std::exception& error) {  // e.g. std::bad_alloc: record it, go on
      report.skipped = failure(error.what());
    }
    worker.tet_s[a] = std::chrono::duration<double>(Clock::now() - t0).count();
    if (!report.skipped.empty()) {
      report.skipped = one_line(report.skipped);
      continue;
    }
    if (const std::string error = tracks_error(tracks, scans); !error.empty()) {
      report.skipped = failure(error);
      continue;
    }
    try {
      worker.metrics[a] = compute_tracking_metrics(scored, tracks, metrics_);
    } catch (const InputError& error) {
      report.skipped = failure(error.what());
      continue;
    }
    if (record_iterations_) score_history(worker, a, scored, scans);
  }
  worker.busy_seconds += std::chrono::duration<double>(Clock::now() - start).count();

  std::string& track_rows = worker.texts[0];
  std::string& measurement_rows = worker.texts[1];
  std::string& trial_rows = worker.texts.back();
  const std::string& prefix = point_prefix_[point];
  const bool item_rows = first_algorithm == 0;  // the truth's and the measurements' rows: once per item
  for (std::size_t i = 0; item_rows && i < truth.targets.size(); ++i) {
    const TrackingTruth::Target& target = truth.targets[i];
    for (int k = 0; k < scans; ++k) {
      if (!target.alive[k]) continue;
      fmt::format_to(std::back_inserter(track_rows), "{},{},truth,{},1,{}", prefix, trial, i + 1, k);
      for (int c = 0; c < kStateColumns; ++c) append_number(track_rows, target.states(c, k));
      track_rows += ",,,,\n";
    }
  }
  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
    if (!worker.reports[a].skipped.empty()) continue;
    for (const Track& track : worker.tracks[a].tracks) {
      for (int s = 0; s < track.length(); ++s) {
        fmt::format_to(std::back_inserter(track_rows), "{},{},{},{},{},{}", prefix, trial, spec_field_[a], track.id,
                       track.confirmed ? 1 : 0, track.first_scan + s);
        for (int c = 0; c < kStateColumns; ++c) append_number(track_rows, track.states(c, s));
        for (int c = 0; c < kStateColumns; ++c) append_number(track_rows, track.covariance_diagonals(c, s));
        track_rows += '\n';
      }
    }
  }

  if (item_rows && trial == 0) {
    for (int k = 0; k < scans; ++k) {
      const Eigen::MatrixXd& scan = problem.scans[k];
      for (Eigen::Index j = 0; j < scan.cols(); ++j) {
        fmt::format_to(std::back_inserter(measurement_rows), "{},{},{}", prefix, trial, k);
        for (Eigen::Index c = 0; c < 3; ++c) append_number(measurement_rows, c < scan.rows() ? scan(c, j) : kNaN);
        const MeasurementOrigin& origin = truth.origin[k][j];
        fmt::format_to(std::back_inserter(measurement_rows), ",{},{}\n", origin.is_clutter() ? -1 : origin.target + 1,
                       origin.is_clutter() ? -1 : origin.path + 1);
      }
    }
  }

  if (record_iterations_) {
    std::string& iteration_rows = worker.texts[2];
    for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
      if (!worker.reports[a].skipped.empty()) continue;
      const std::vector<TrackingMetrics>& history = worker.iteration_metrics[a];
      for (std::size_t r = 0; r < history.size(); ++r) {
        fmt::format_to(std::back_inserter(iteration_rows), "{},{},{},{},{}", prefix, trial, plan_.seed, spec_field_[a],
                       r);
        append_metrics(iteration_rows, history[r]);
        append_number(iteration_rows, worker.histories[a][r].objective);
        iteration_rows += '\n';
      }
    }
  }

  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
    const SolveReport& report = worker.reports[a];
    const bool ok = report.skipped.empty();
    const TrackingMetrics m = ok ? worker.metrics[a] : kMissing;
    fmt::format_to(std::back_inserter(trial_rows), "{},{},{},{},", prefix, trial, plan_.seed, spec_field_[a]);
    append_status(trial_rows, report);
    append_metrics(trial_rows, m);
    append_number(trial_rows, worker.tet_s[a]);
    append_number(trial_rows, ok ? report.iterations : kNaN);
    append_number(trial_rows, ok ? (report.converged ? 1.0 : 0.0) : kNaN);
    append_number(trial_rows, ok ? report.free_energy : kNaN);
    trial_rows += '\n';
  }
}

}  // namespace dabench
