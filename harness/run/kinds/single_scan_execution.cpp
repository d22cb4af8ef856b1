#include "harness/run/kinds/single_scan_execution.hpp"

#include <chrono>
#include <exception>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "harness/core/row_fields.hpp"
#include "harness/run/trial_draw.hpp"
#include "harness/single_scan/marginal_errors.hpp"
#include "harness/single_scan/registry.hpp"

namespace dabench {

namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

SingleScanExecution::SingleScanExecution(const RunPlan& plan, std::vector<std::unique_ptr<SingleScanScenario>> scenarios)
    : plan_(plan),
      scenarios_(std::move(scenarios)),
      point_prefix_(plan.point_row_prefixes()),
      spec_field_(plan.spec_fields()) {}

std::unique_ptr<RunWorker> SingleScanExecution::make_worker() const {
  auto made = std::make_unique<SingleScanWorker>();
  SingleScanWorker& worker = *made;
  for (const std::string& spec : plan_.specs) worker.solvers.push_back(make_single_scan_solver(spec));
  worker.marginals.resize(plan_.specs.size());
  worker.reports.resize(plan_.specs.size());
  worker.time_us.resize(plan_.specs.size());
  worker.texts.resize(1);  // trials.csv
  return made;
}

void SingleScanExecution::run_unit(RunWorker& worker, long long item, std::size_t part) const {
  static_cast<void>(part);  // one unit per item: every algorithm
  run_item(static_cast<SingleScanWorker&>(worker), item);
}

void SingleScanExecution::run_item(SingleScanWorker& worker, long long item) const {
  const auto start = Clock::now();
  const auto [point, trial] = draw_trial(plan_, scenarios_, item, worker.sample);
  worker.sample.problem.trial_key = {plan_.seed, point, trial};
  const SingleScanProblem& problem = worker.sample.problem;
  const std::size_t count = worker.solvers.size();
  const auto references = static_cast<std::size_t>(plan_.references);
  std::size_t reference = count;  // index of the reference used in this trial (count = none)
  for (std::size_t a = 0; a < count; ++a) {
    SolveReport& report = worker.reports[a];
    if (a < references && reference < count) {  // a fallback reference that is not needed
      report.reset();
      report.skipped = "not_needed";
      worker.time_us[a] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const auto t0 = Clock::now();
    try {
      if (!refuse_must_detect(*worker.solvers[a], problem, report)) worker.solvers[a]->solve(problem, worker.marginals[a], report);
    } catch (const std::exception& error) {  // e.g. std::bad_alloc: record it, go on
      report.skipped = "failed:" + one_line(error.what());
    }
    worker.time_us[a] = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    reject_non_distribution(problem, worker.marginals[a], report);
    if (a < references && report.skipped.empty()) reference = a;
  }
  worker.busy_seconds += std::chrono::duration<double>(Clock::now() - start).count();

  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t a = 0; a < count; ++a) {
    const SolveReport& report = worker.reports[a];
    std::string& row = worker.texts[0];
    fmt::format_to(std::back_inserter(row), "{},{},{},{},", point_prefix_[point], trial, plan_.seed, spec_field_[a]);
    const bool ok = report.skipped.empty();
    append_status(row, report);
    fmt::format_to(std::back_inserter(row), ",{},{}", problem.targets(), problem.measurements());
    MarginalErrors errors{nan, nan};
    if (ok && reference < count && problem.targets() > 0) {
      errors = marginal_errors(worker.marginals[a], worker.marginals[reference]);
    }
    append_number(row, errors.max_error);
    append_number(row, errors.mean_error);
    append_number(row, worker.time_us[a]);
    append_number(row, ok ? report.iterations : nan);
    append_number(row, ok ? (report.converged ? 1.0 : 0.0) : nan);
    append_number(row, report.w_star);
    row += '\n';
  }
}

}  // namespace dabench
