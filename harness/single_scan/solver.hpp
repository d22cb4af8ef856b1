#pragma once
// The interface of single-scan algorithms: ψ (plus side weights and context) in, marginals
// p(a_i = j) out. One solver object serves one thread for a whole run, so it keeps its
// workspace between calls and a solve does not allocate once buffers have grown.
#include "harness/core/marginal_table.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/single_scan/problem.hpp"

namespace dabench {

class SingleScanSolver {
 public:
  virtual ~SingleScanSolver() = default;
  // Fills `marginals` (n×(m+1), rows summing to one) unless report.skipped is set.
  // `problem` has passed SingleScanProblem::validate().
  virtual void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) = 0;
  // Whether solve() handles targets that must be detected (SingleScanProblem::must_detect, a
  // zero missed-detection weight): the exact methods that enumerate events or partial events.
  // The others work in the ψ_i(0) = 1 form of eq (9), which cannot express it.
  virtual bool accepts_must_detect() const { return false; }
};

// Before a solve: a problem with a target that must be detected, for a solver that cannot
// express it, is recorded as skipped:zero_miss_weight (returns true; solve() is not called).
bool refuse_must_detect(const SingleScanSolver& solver, const SingleScanProblem& problem, SolveReport& report);

// After a solve that was not skipped: a table that is not a distribution per target (a NaN or
// infinite entry, one outside [0, 1], a row whose sum is more than 1e-6 from one), e.g. from an
// overflow, is recorded as skipped:numerical, so no metric is computed from it. Every caller of
// solve() (the runner, the library entry point, `dabench solve`) applies it.
void reject_non_distribution(const SingleScanProblem& problem, const MarginalTable& marginals, SolveReport& report);

}  // namespace dabench
