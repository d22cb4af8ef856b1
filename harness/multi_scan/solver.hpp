#pragma once
// The interface of multiple-scan algorithms (multiscan-convex-variational): a MultiScanProblem
// in, beliefs q^i(A^i) and per-scan association beliefs q^{i,j}_t' out. Sequential methods
// (CVS, JPDA-BP) take the scans in the problem's order and report the beliefs after the last.
// As for single-scan solvers, one object serves one thread for a whole run.
#include "harness/core/solve_report.hpp"
#include "harness/multi_scan/problem.hpp"

namespace dabench {

class MultiScanSolver {
 public:
  virtual ~MultiScanSolver() = default;
  // Fills `beliefs` unless report.skipped is set. `problem` has passed validate().
  virtual void solve(const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) = 0;
};

}  // namespace dabench
