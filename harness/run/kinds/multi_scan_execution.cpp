#include "harness/run/kinds/multi_scan_execution.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "harness/core/csv.hpp"
#include "harness/core/row_fields.hpp"
#include "harness/multi_scan/particle_metrics.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/run/trial_draw.hpp"

namespace dabench {

namespace {

using Clock = std::chrono::steady_clock;

// The beliefs must cover the problem's tracks and hypotheses; otherwise the solver is broken.
std::string shape_error(const MultiScanProblem& problem, const MultiScanBeliefs& beliefs) {
  if (static_cast<int>(beliefs.track.size()) != problem.tracks()) {
    return fmt::format("failed:beliefs for {} tracks, expected {}", beliefs.track.size(), problem.tracks());
  }
  for (int i = 0; i < problem.tracks(); ++i) {
    if (beliefs.track[i].size() != problem.hypotheses(i)) {
      return fmt::format("failed:track {} belief has {} entries, expected {}", i + 1, beliefs.track[i].size(),
                         problem.hypotheses(i));
    }
  }
  return {};
}

}  // namespace

MultiScanExecution::MultiScanExecution(const RunPlan& plan, std::vector<std::unique_ptr<MultiScanScenario>> scenarios)
    : plan_(plan),
      scenarios_(std::move(scenarios)),
      point_prefix_(plan.point_row_prefixes()),
      spec_field_(plan.spec_fields()) {}

std::unique_ptr<RunWorker> MultiScanExecution::make_worker() const {
  auto made = std::make_unique<MultiScanWorker>();
  MultiScanWorker& worker = *made;
  for (const std::string& spec : plan_.specs) worker.solvers.push_back(make_multi_scan_solver(spec));
  worker.beliefs.resize(plan_.specs.size());
  worker.reports.resize(plan_.specs.size());
  worker.time_us.resize(plan_.specs.size());
  worker.texts.resize(2);  // targets.csv, trials.csv
  return made;
}

void MultiScanExecution::run_unit(RunWorker& worker, long long item, std::size_t part) const {
  run_item(static_cast<MultiScanWorker&>(worker), item, part, part + 1);
}

void MultiScanExecution::run_item(MultiScanWorker& worker, long long item, std::size_t first_algorithm,
                                  std::size_t end_algorithm) const {
  const auto start = Clock::now();
  const auto [point, trial] = draw_trial(plan_, scenarios_, item, worker.sample);
  const MultiScanProblem& problem = worker.sample.problem;
  const int n = problem.tracks();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
    SolveReport& report = worker.reports[a];
    report.reset();
    worker.time_us[a] = nan;
    if (n == 0) {
      report.skipped = "no_targets";
      continue;
    }
    const auto t0 = Clock::now();
    try {
      worker.solvers[a]->solve(problem, worker.beliefs[a], report);
    } catch (const std::exception& error) {  // e.g. std::bad_alloc: record it, go on
      report.skipped = "failed:" + one_line(error.what());
    }
    worker.time_us[a] = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    if (report.skipped.empty()) report.skipped = shape_error(problem, worker.beliefs[a]);
  }
  worker.busy_seconds += std::chrono::duration<double>(Clock::now() - start).count();

  int measurements = 0;
  for (const ScanFactors& scan : problem.scans) measurements += scan.measurements;
  std::string& targets = worker.texts[0];
  std::string& trials = worker.texts[1];
  for (std::size_t a = first_algorithm; a < end_algorithm; ++a) {
    const SolveReport& report = worker.reports[a];
    const bool ok = report.skipped.empty();
    double hpd_sum = 0.0, hpd_max = nan, entropy_sum = 0.0;
    for (int i = 0; i < n; ++i) {
      ParticleBeliefMetrics metrics{nan, nan, nan};
      if (ok) {
        metrics = particle_belief_metrics(worker.beliefs[a].track[i], worker.sample.density_scale[i], problem.prior[i],
                                          worker.sample.truth_probe[i]);
        hpd_sum += metrics.hpd;
        hpd_max = i == 0 ? metrics.hpd : std::max(hpd_max, metrics.hpd);
        entropy_sum += metrics.entropy;
      }
      fmt::format_to(std::back_inserter(targets), "{},{},{},{},{}", point_prefix_[point], trial, plan_.seed,
                     spec_field_[a], i + 1);
      append_number(targets, metrics.hpd);
      append_number(targets, metrics.entropy);
      append_number(targets, metrics.hpd_likelihood);
      targets += '\n';
    }
    fmt::format_to(std::back_inserter(trials), "{},{},{},{},", point_prefix_[point], trial, plan_.seed, spec_field_[a]);
    append_status(trials, report);
    fmt::format_to(std::back_inserter(trials), ",{},{},{}", n, problem.scan_count(), measurements);
    const bool measured = ok && n > 0;
    append_number(trials, measured ? hpd_sum / n : nan);
    append_number(trials, measured ? hpd_max : nan);
    append_number(trials, measured ? entropy_sum / n : nan);
    append_number(trials, worker.time_us[a]);
    append_number(trials, ok ? report.iterations : nan);
    append_number(trials, ok ? (report.converged ? 1.0 : 0.0) : nan);
    append_number(trials, ok && report.line_search_steps >= 0 ? report.line_search_steps : nan);
    append_number(trials, ok ? report.residual : nan);
    append_number(trials, ok ? report.inner_residual : nan);
    trials += '\n';
  }
}

}  // namespace dabench
