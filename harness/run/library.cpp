#include "harness/run/library.hpp"

#include <chrono>
#include <exception>
#include <utility>

#include "harness/core/row_fields.hpp"

namespace dabench {

SingleScanProblem make_single_scan_problem(RowMatrix psi, ScanContext context) {
  SingleScanProblem problem;
  problem.psi = std::move(psi);
  problem.context = context;
  if (const std::string why = problem.validate(); !why.empty()) throw InputError("problem: " + why);
  return problem;
}

SingleScanResult solve_single_scan(std::string_view spec, const SingleScanProblem& problem) {
  const auto solver = make_single_scan_solver(spec);
  return solve_single_scan(*solver, problem);
}

SingleScanResult solve_single_scan(SingleScanSolver& solver, const SingleScanProblem& problem) {
  if (const std::string why = problem.validate(); !why.empty()) throw InputError("problem: " + why);
  SingleScanResult result;
  try {
    if (!refuse_must_detect(solver, problem, result.report)) solver.solve(problem, result.marginals, result.report);
  } catch (const std::exception& error) {  // as the runner: a failed solve is a status
    result.report.skipped = "failed:" + one_line(error.what());
  }
  reject_non_distribution(problem, result.marginals, result.report);
  if (!result.report.skipped.empty()) result.marginals = MarginalTable();
  return result;
}

RepeatTiming time_single_scan(SingleScanSolver& solver, const SingleScanProblem& problem, const RepeatTimingOptions& options) {
  MarginalTable marginals;
  SolveReport report;
  return time_repeatedly(
      [&](long long calls) {
        const auto start = std::chrono::steady_clock::now();
        for (long long call = 0; call < calls; ++call) solver.solve(problem, marginals, report);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      },
      options);
}

}  // namespace dabench
