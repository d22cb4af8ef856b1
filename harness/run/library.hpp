#pragma once
// dabench as a C++ library: the public entry point (docs/cpp-library.md).
// Link dabench::dabench, which brings every registered algorithm and scenario; this header
// names none of them.
//
//   SingleScanProblem problem = make_single_scan_problem(psi);          // ψ, n×m (eq 11)
//   SingleScanResult r = solve_single_scan("bp:delta=1e-9", problem);  // by SPEC, as `dabench solve`
//   SingleScanResult t = solve_single_scan<BeliefPropagation>(problem, {.delta = 1e-9});  // typed
//   RunOptions run;                                                      // as `dabench run`
//   run.experiment_path = "quickstart.ini";
//   run.output = "out";                      // overrides the file's output (also trials, seed, ...)
//   RunOutcome outcome = run_experiment(run);  // InputError for anything wrong before it starts
//
// An algorithm written outside dabench registers itself with one line in its source file,
// DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(MyAlgorithm) (multi scan: DABENCH_REGISTER_MULTI_SCAN_ALGORITHM, trackers:
// DABENCH_REGISTER_TRACKING_TRACKER; see harness/<kind>/registry.hpp for what the class provides). Its
// object file must be linked into the program itself (or as an OBJECT library or a whole
// archive): the registration is a static object that nothing references.
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

#include "harness/core/errors.hpp"
#include "harness/core/marginal_table.hpp"
#include "harness/core/matrix_types.hpp"
#include "harness/core/repeat_timing.hpp"
#include "harness/core/solve_report.hpp"
#include "harness/run/runner.hpp"
#include "harness/single_scan/problem.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/single_scan/solver.hpp"
#include "harness/single_scan/weights_csv.hpp"

namespace dabench {

// One solved single-scan problem.
struct SingleScanResult {
  // p(a_i = j), n×(m+1), column 0 = missed detection, rows summing to one; 0×0 when the
  // algorithm did not solve (report.skipped set).
  MarginalTable marginals;
  // Diagnostics: iterations, converged, W* (Lemma 2), free energy, ... as in trials.csv.
  // report.skipped: empty = solved; else the algorithm's reason for refusing the problem (e.g.
  // "needs_pd", "work_limit"), or "failed:<what>" if it threw (as the runner records it).
  SolveReport report;
};

// The problem of eqs (9)-(11) from ψ (n targets × m measurements, ψ_i(j) ≥ 0, ψ_i(0) = 1
// implied) and the model constants some algorithms need (e.g. lmipda: Pd). Throws InputError
// naming the first bad entry (negative, NaN or infinite).
SingleScanProblem make_single_scan_problem(RowMatrix psi, ScanContext context = {});

// Solves `problem` with the algorithm named by SPEC ("name" or "name:key=value,..."). Throws
// InputError for an unknown name or key, a bad value, or a problem that fails validate().
SingleScanResult solve_single_scan(std::string_view spec, const SingleScanProblem& problem);

// Solves with a solver made once (make_single_scan_solver(spec), or a typed algorithm object),
// e.g. to reuse its buffers over many problems. Throws InputError for an invalid problem.
SingleScanResult solve_single_scan(SingleScanSolver& solver, const SingleScanProblem& problem);

// Times `solver` on `problem` as `dabench solve --time` does: its calls alone, repeated on the
// same input (warm caches) until the median is stable or the budget is spent
// (harness/core/repeat_timing.hpp). `problem` has passed validate().
RepeatTiming time_single_scan(SingleScanSolver& solver, const SingleScanProblem& problem, const RepeatTimingOptions& options);

// Solves with a typed options struct: the algorithm class needs no registration, and
// `options` is checked by its validate() exactly as a SPEC's values are (same InputError
// message, "name: rule"), so equal values give bit-identical results by either path.
template <class Algorithm>
SingleScanResult solve_single_scan(const SingleScanProblem& problem, const typename Algorithm::Options& options = {}) {
  static_assert(std::is_base_of_v<SingleScanSolver, Algorithm>, "Algorithm must implement SingleScanSolver");
  if (const std::string why = options.validate(); !why.empty()) {
    throw InputError(std::string(Algorithm::kName) + ": " + why);
  }
  const auto solver = std::make_unique<Algorithm>(options);  // solvers may be large or non-movable
  return solve_single_scan(*solver, problem);
}

}  // namespace dabench
