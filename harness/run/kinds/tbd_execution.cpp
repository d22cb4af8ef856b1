#include "harness/core/special_values.hpp"
#include "harness/run/kinds/tbd_execution.hpp"

#include <chrono>

#include <fmt/format.h>

#include "harness/core/row_fields.hpp"
#include "harness/run/trial_draw.hpp"
#include "harness/tbd/registry.hpp"

namespace dabench {

namespace {

using Clock = std::chrono::steady_clock;

void append_step_metrics(std::string& row, const TbdStepMetrics& m) {
  for (const double value : {static_cast<double>(m.objects), static_cast<double>(m.estimates), m.gospa, m.gospa_p2,
                             m.localisation, m.missed, m.false_objects}) {
    append_number(row, value);
  }
}

void append_estimate(std::string& row, int label, double existence, double x, double y, double vx, double vy) {
  fmt::format_to(std::back_inserter(row), ",{}", label);
  for (const double value : {existence, x, y, vx, vy}) append_number(row, value);
  row += '\n';
}

}  // namespace

std::string tbd_metrics_json(const TbdMetricsOptions& options) {
  return fmt::format(R"({{"gospa_cutoff": {}, "gospa_order": {}, "gospa_alpha": {}}})", options.gospa_cutoff,
                     options.gospa_order, options.gospa_alpha);
}

TbdExecution::TbdExecution(const RunPlan& plan, std::vector<std::unique_ptr<TbdScenario>> scenarios,
                           const TbdMetricsOptions& metrics)
    : plan_(plan),
      scenarios_(std::move(scenarios)),
      metrics_(metrics),
      point_prefix_(plan.point_row_prefixes()),
      spec_field_(plan.spec_fields()) {}

std::unique_ptr<RunWorker> TbdExecution::make_worker() const {
  auto made = std::make_unique<TbdWorker>();
  TbdWorker& worker = *made;
  for (const std::string& spec : plan_.specs) worker.trackers.push_back(make_tbd_tracker(spec));
  const std::size_t count = plan_.specs.size();
  worker.reports.resize(count);
  worker.steps.resize(count);
  worker.step_seconds.resize(count);
  worker.reported.resize(count);
  worker.scorer = std::make_unique<TbdScorer>(metrics_);
  worker.texts.resize(plan_.experiment.record_beliefs ? 5 : 4);  // steps, estimates, frames, [beliefs,] trials.csv
  return made;
}

void TbdExecution::run_unit(RunWorker& worker, long long item, std::size_t part) const {
  run_item(static_cast<TbdWorker&>(worker), item, part, part + 1);
}

void TbdExecution::run_tracker(TbdWorker& worker, std::size_t a, bool keep_estimates) const {
  const TbdProblem& problem = worker.sample.problem;
  SolveReport& report = worker.reports[a];
  SolveReport step_report;
  report.reset();
  worker.steps[a].clear();
  worker.step_seconds[a].clear();
  worker.reported[a].clear();
  try {
    worker.trackers[a]->start(problem);
    for (int k = 0; k < problem.steps(); ++k) {
      step_report.reset();
      const auto t0 = Clock::now();
      worker.trackers[a]->step(k, worker.estimates, step_report);
      worker.step_seconds[a].push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      if (!step_report.skipped.empty()) {
        report.skipped = one_line(step_report.skipped);
        return;
      }
      report.iterations += step_report.iterations;
      report.converged = report.converged && step_report.converged;
      worker.steps[a].push_back(worker.scorer->score(worker.sample.truth, k, worker.estimates));
      if (keep_estimates) worker.reported[a].push_back(worker.estimates);
    }
  } catch (const std::exception& error) {  // e.g. std::bad_alloc: record it, go on
    report.skipped = "failed:" + one_line(error.what());
  }
}

void TbdExecution::run_item(TbdWorker& worker, long long item, std::size_t first_algorithm,
                            std::size_t end_algorithm) const {
  const auto start = Clock::now();
  const auto [point, trial] = draw_trial(plan_, scenarios_, item, worker.sample);
  worker.sample.problem.trial_key = {plan_.seed, point, trial};
  const TbdProblem& problem = worker.sample.problem;
  const TbdTruth& truth = worker.sample.truth;
  const int steps = problem.steps();
  const bool first_trial = trial == 0;
  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) run_tracker(worker, a, first_trial);
  worker.busy_seconds += std::chrono::duration<double>(Clock::now() - start).count();

  std::string& step_rows = worker.texts[0];
  std::string& estimate_rows = worker.texts[1];
  std::string& frame_rows = worker.texts[2];
  std::string& trial_rows = worker.texts.back();
  const std::string& prefix = point_prefix_[point];
  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
    if (!worker.reports[a].skipped.empty()) continue;
    for (int k = 0; k < steps; ++k) {
      fmt::format_to(std::back_inserter(step_rows), "{},{},{},{},{}", prefix, trial, plan_.seed, spec_field_[a], k + 1);
      append_step_metrics(step_rows, worker.steps[a][k]);
      append_number(step_rows, 1e6 * worker.step_seconds[a][k]);
      step_rows += '\n';
    }
  }

  const bool item_rows = first_algorithm == 0;  // the truth's and the frames' rows: once per item
  if (first_trial) {
    for (std::size_t i = 0; item_rows && i < truth.objects.size(); ++i) {
      const TbdTruth::Object& object = truth.objects[i];
      for (int k = 0; k < steps; ++k) {
        if (!object.alive[k]) continue;
        fmt::format_to(std::back_inserter(estimate_rows), "{},{},truth,{}", prefix, trial, k + 1);
        append_estimate(estimate_rows, static_cast<int>(i) + 1, 1.0, object.states(0, k), object.states(1, k),
                        object.states(2, k), object.states(3, k));
      }
    }
    for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
      if (!worker.reports[a].skipped.empty()) continue;
      for (int k = 0; k < steps; ++k) {
        for (const TbdEstimate& e : worker.reported[a][k]) {
          fmt::format_to(std::back_inserter(estimate_rows), "{},{},{},{}", prefix, trial, spec_field_[a], k + 1);
          append_estimate(estimate_rows, e.label, e.existence, e.state(0), e.state(1), e.state(2), e.state(3));
        }
      }
    }
    const TbdSensor& sensor = problem.sensor;
    for (int k = 0; item_rows && k < steps; ++k) {
      const Eigen::Matrix2Xd& frame = problem.frames[k];
      for (int row = 0; row < sensor.rows; ++row) {
        for (int column = 0; column < sensor.columns; ++column) {
          const int j = row * sensor.columns + column;
          fmt::format_to(std::back_inserter(frame_rows), "{},{},{},{},{}", prefix, trial, k + 1, column, row);
          append_number(frame_rows, frame(0, j));
          append_number(frame_rows, frame(1, j));
          frame_rows += '\n';
        }
      }
    }
  }

  if (first_trial && plan_.experiment.record_beliefs) {
    std::string& belief_rows = worker.texts[3];
    for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
      if (!worker.reports[a].skipped.empty()) continue;
      worker.trackers[a]->beliefs(worker.belief_samples);
      for (const TbdBeliefSample& b : worker.belief_samples) {
        fmt::format_to(std::back_inserter(belief_rows), "{},{},{},{},{}", prefix, trial, spec_field_[a], steps, b.label);
        for (const double value : {b.existence, b.x, b.y, b.weight}) append_number(belief_rows, value);
        belief_rows += '\n';
      }
    }
  }

  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
    const SolveReport& report = worker.reports[a];
    const bool ok = report.skipped.empty();
    fmt::format_to(std::back_inserter(trial_rows), "{},{},{},{},", prefix, trial, plan_.seed, spec_field_[a]);
    append_status(trial_rows, report);
    append_number(trial_rows, steps);
    // Means over the run's steps.
    double sums[8] = {};
    if (ok) {
      for (int k = 0; k < steps; ++k) {
        const TbdStepMetrics& m = worker.steps[a][k];
        const double values[8] = {m.gospa,   m.gospa_p2, m.localisation, m.missed, m.false_objects,
                                  static_cast<double>(m.objects), static_cast<double>(m.estimates),
                                  1e6 * worker.step_seconds[a][k]};
        for (int c = 0; c < 8; ++c) sums[c] += values[c];
      }
    }
    for (const double sum : sums) append_number(trial_rows, ok && steps > 0 ? sum / steps : kNaN);
    append_number(trial_rows, ok ? report.iterations : kNaN);
    append_number(trial_rows, ok ? (report.converged ? 1.0 : 0.0) : kNaN);
    trial_rows += '\n';
  }
}

}  // namespace dabench
