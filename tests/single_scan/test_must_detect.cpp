// Targets that must be detected (a zero missed-detection weight, Pd = 1, as the Tracker
// Component Library and Stone Soup accept): the exact methods that take them (exact, ehm in
// every variant) against the brute-force oracle of the general form (w_i0 = 0 excludes every
// event that misses target i); an infeasible problem (no event detects them all) is
// skipped:infeasible; the other methods, in the ψ_i(0) = 1 form, refuse with
// skipped:zero_miss_weight; the tcl and stonesoup layouts read a zero miss weight as such a target.
#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <vector>

#include "harness/run/library.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/single_scan/weights_layout.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

const char* const kExactSpecs[] = {"exact",       "ehm",         "ehm:tree=0", "ehm:order=1",
                                   "ehm:order=2", "ehm:order=3", "ehm:order=3,tree=0"};

// A random problem of the general form with targets 0, 2, 4, ... (those with `must` set) that
// must be detected.
SingleScanProblem with_must_detect(RandomStream& rng, int n, int m, Density density) {
  SingleScanProblem problem = random_problem(rng, n, m, density, /*side_weights=*/true);
  for (int i = 0; i < n; i += 2) problem.miss_weight[i] = 0.0;
  return problem;
}

TEST_CASE("must-detect targets: exact and ehm equal the brute force; infeasible problems are named", "[must_detect]") {
  RandomStream rng(47, 8, 0);
  int feasible = 0, infeasible = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = uniform_int(rng, 1, 5), m = uniform_int(rng, 0, 5);
    const SingleScanProblem problem = with_must_detect(rng, n, m, cycled_density(trial));
    REQUIRE(problem.validate().empty());
    const BruteForceResult oracle = brute_force_marginals(problem);
    (oracle.positive_events > 0 ? feasible : infeasible) += 1;
    for (const char* spec : kExactSpecs) {
      INFO("trial " << trial << ", " << spec << ", n " << n << ", m " << m);
      const auto solver = make_single_scan_solver(spec);
      const SolveResult result = run_solver(*solver, problem);
      if (oracle.positive_events == 0) {
        CHECK(result.report.skipped == "infeasible");
        continue;
      }
      REQUIRE(result.report.skipped.empty());
      CHECK(scaled_error(result.marginals, oracle.marginals, 1e-9, 1e-12) <= 1.0);
      for (int i = 0; i < n; i += 2) CHECK(result.marginals(i, 0) == 0.0);
    }
  }
  // Both kinds occur in the sweep.
  CHECK(feasible > 150);
  CHECK(infeasible > 10);
}

TEST_CASE("must-detect targets: the methods in the psi_i(0) = 1 form refuse with a status", "[must_detect]") {
  RandomStream rng(47, 9, 0);
  const SingleScanProblem problem = with_must_detect(rng, 3, 4, Density::dense);
  for (const char* spec : {"bp", "jt", "permanent", "mcmcda", "baa", "lmipda", "cheap-jpda", "fbp"}) {
    INFO(spec);
    const SingleScanResult result = solve_single_scan(spec, problem);
    CHECK(result.report.skipped == "zero_miss_weight");
  }
  CHECK(solve_single_scan("exact", problem).report.skipped.empty());
}

TEST_CASE("must-detect targets: tcl and stonesoup read a zero missed-detection weight as one", "[must_detect]") {
  // Two targets, three measurements; target 1's missed detection 0 (Pd = 1), target 2's 0.5.
  // tcl: w_ij, then the diagonal block of missed-detection weights.
  RowMatrix tcl(2, 5);
  tcl << 0.2, 0.4, 0.0, 0.0, 0.0,  //
      0.3, 0.0, 0.6, 0.0, 0.5;
  RowMatrix stonesoup(2, 4);
  stonesoup << 0.0, 0.2, 0.4, 0.0,  //
      0.5, 0.3, 0.0, 0.6;
  // The general form's oracle: events (a1 in {1, 2}) × (a2 in {0, 1, 3}), a1 ≠ a2.
  SingleScanProblem general;
  general.psi = RowMatrix(2, 3);
  general.psi << 0.2, 0.4, 0.0,  //
      0.3, 0.0, 0.6;
  general.miss_weight = Vector(2);
  general.miss_weight << 0.0, 0.5;
  const BruteForceResult oracle = brute_force_marginals(general);
  for (const auto& [matrix, layout] : {std::pair{tcl, WeightsLayout::tcl}, std::pair{stonesoup, WeightsLayout::stonesoup}}) {
    INFO(weights_layout_name(layout));
    const SingleScanProblem problem = problem_from_weights(matrix, {layout, false}, "w.csv");
    CHECK(problem.must_detect(0));
    CHECK_FALSE(problem.must_detect(1));
    for (const char* spec : {"exact", "ehm"}) {
      const SingleScanResult result = solve_single_scan(spec, problem);
      REQUIRE(result.report.skipped.empty());
      CHECK(max_abs_difference(to_matrix(result.marginals), oracle.marginals) < 1e-15);
    }
    // In log form too: −inf is a weight of 0.
    RowMatrix logs = matrix.array().log();
    const SingleScanProblem from_logs = problem_from_weights(logs, {layout, true}, "w.csv");
    CHECK(max_abs_difference(to_matrix(solve_single_scan("exact", from_logs).marginals), oracle.marginals) < 1e-14);
  }
  // By hand: Z = 0.2·(0.5 + 0.6) + 0.4·(0.5 + 0.3 + 0.6) = 0.22 + 0.56 = 0.78.
  CHECK(oracle.marginals(0, 1) == Approx(0.22 / 0.78).epsilon(1e-14));
  CHECK(oracle.marginals(1, 0) == Approx((0.2 * 0.5 + 0.4 * 0.5) / 0.78).epsilon(1e-14));
}

}  // namespace DABENCH_TEST_FILE
