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
};

}  // namespace dabench
