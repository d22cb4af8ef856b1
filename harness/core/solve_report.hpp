#pragma once
// What one solve of any kind reports beside its result: skipped or solved, iterations,
// convergence and the method's diagnostics. Written to trials.csv by the runner.
#include <limits>
#include <string>

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
  // Methods that keep part of the events (k-best JPDA): the probability mass of the events kept,
  // 1 when every event was (NaN: not computed).
  double captured_mass = std::numeric_limits<double>::quiet_NaN();

  void reset() {
    skipped.clear();
    iterations = 0;
    converged = true;
    w_star = std::numeric_limits<double>::quiet_NaN();
    free_energy = std::numeric_limits<double>::quiet_NaN();
    line_search_steps = -1;
    residual = std::numeric_limits<double>::quiet_NaN();
    inner_residual = std::numeric_limits<double>::quiet_NaN();
    captured_mass = std::numeric_limits<double>::quiet_NaN();
  }
};

}  // namespace dabench
