#include "harness/run/library.hpp"

#include <exception>
#include <utility>

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
    solver.solve(problem, result.marginals, result.report);
  } catch (const std::exception& error) {  // as the runner: a failed solve is a status
    result.report.skipped = std::string("failed:") + error.what();
  }
  reject_non_distribution(problem, result.marginals, result.report);
  if (!result.report.skipped.empty()) result.marginals = MarginalTable();
  return result;
}

}  // namespace dabench
