#pragma once
// The interface of single-scan algorithms: ψ (plus side weights and context) in, marginals
// p(a_i = j) out. One solver object serves one thread for a whole run, so it keeps its
// workspace between calls and a solve does not allocate once buffers have grown.
#include <limits>
#include <string>

#include "harness/marginal_table.hpp"
#include "harness/single_scan_problem.hpp"

namespace dabench {

// What happened in one solve (Ceres style: the run reports, the caller decides).
struct SolveReport {
  std::string skipped;   // empty = solved; else the reason, recorded as "skipped:<reason>"
  int iterations = 0;    // for iterative methods; 0 otherwise
  bool converged = true; // false if an iteration cap stopped the method first
  double w_star = std::numeric_limits<double>::quiet_NaN();  // W* of Lemma 2 where computed
  double free_energy = std::numeric_limits<double>::quiet_NaN();  // objective at the solution where defined (fbp: eq 138)
  // Methods with a line search and a measured optimality residual (the column-dual Newton solver
  // of cv/cvs): backtracking steps in all, and the largest final residuals (NaN / −1: not reported).
  int line_search_steps = -1;
  double residual = std::numeric_limits<double>::quiet_NaN();
  double inner_residual = std::numeric_limits<double>::quiet_NaN();

  void reset() {
    skipped.clear();
    iterations = 0;
    converged = true;
    w_star = std::numeric_limits<double>::quiet_NaN();
    free_energy = std::numeric_limits<double>::quiet_NaN();
    line_search_steps = -1;
    residual = std::numeric_limits<double>::quiet_NaN();
    inner_residual = std::numeric_limits<double>::quiet_NaN();
  }
};

class SingleScanSolver {
 public:
  virtual ~SingleScanSolver() = default;
  // Fills `marginals` (n×(m+1), rows summing to one) unless report.skipped is set.
  // `problem` has passed SingleScanProblem::validate().
  virtual void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) = 0;
};

}  // namespace dabench
