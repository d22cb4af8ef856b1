#include "harness/single_scan/solver.hpp"

#include <cmath>

namespace dabench {

bool refuse_must_detect(const SingleScanSolver& solver, const SingleScanProblem& problem, SolveReport& report) {
  if (solver.accepts_must_detect() || !problem.has_must_detect_targets()) return false;
  report.reset();
  report.skipped = "zero_miss_weight";
  return true;
}

void reject_non_distribution(const SingleScanProblem& problem, const MarginalTable& marginals, SolveReport& report) {
  if (!report.skipped.empty()) return;
  constexpr double kRowTolerance = 1e-6;  // far above rounding, far below any real mass
  const int columns = problem.measurements() + 1;
  for (int i = 0; i < problem.targets(); ++i) {
    const double* row = marginals.row(i);
    double sum = 0.0;
    for (int j = 0; j < columns; ++j) {
      if (!(row[j] >= 0.0 && row[j] <= 1.0 + kRowTolerance)) {  // false for NaN too
        report.skipped = "numerical";
        return;
      }
      sum += row[j];
    }
    if (!(std::abs(sum - 1.0) <= kRowTolerance)) {
      report.skipped = "numerical";
      return;
    }
  }
}

}  // namespace dabench
