// Tests of the exact permanent (algorithms/single_scan/permanent.hpp) against brute-force
// enumeration: to 1e-12 on random problems of either shape (more targets or more measurements)
// and with weights from 1e-100 to 1e100; its memory limit, and its refusal where underflow in
// its scaled layers could move a probability.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

TEST_CASE("permanent: equals enumeration on random problems of either shape", "[permanent]") {
  RandomStream rng(41, 0, 0);
  double worst = 0.0;
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 1 + static_cast<int>(rng.uniform() * 6), m = static_cast<int>(rng.uniform() * 7);
    const SingleScanProblem problem = gated_exponential_problem(rng, n, m, trial % 2 == 0 ? 1.0 : 0.4);
    const SolveResult result = run_solver(*make_single_scan_solver("permanent"), problem);
    REQUIRE(result.report.skipped.empty());
    worst = std::max(worst, (result.marginals - brute_force_marginals(problem).marginals).cwiseAbs().maxCoeff());
  }
  CHECK(worst < 1e-12);
}

TEST_CASE("permanent: huge and tiny weights, and the memory limit", "[permanent]") {
  SingleScanProblem problem;
  problem.psi = RowMatrix(3, 3);
  problem.psi << 1e100, 1e-100, 3,  // events up to 1e300: the brute force's products stay finite
                 2, 1e100, 1e-80,
                 1e50, 5, 1e100;
  const SolveResult result = run_solver(*make_single_scan_solver("permanent"), problem);
  REQUIRE(result.report.skipped.empty());
  CHECK((result.marginals - brute_force_marginals(problem).marginals).cwiseAbs().maxCoeff() < 1e-12);
  RandomStream rng(43, 0, 0);
  const SingleScanProblem big = gated_exponential_problem(rng, 24, 24, 1.0);  // 27 · 2^24 doubles: 3.4 GiB
  CHECK(run_solver(*make_single_scan_solver("permanent:memory_mb=1024"), big).report.skipped == "memory");
}

TEST_CASE("permanent: refuses where underflow in its scaled layers could move a probability", "[permanent]") {
  // A fuzzer's find: targets 2 and 3 are identical, so their marginals must be; the product of a
  // scaled forward entry (1e-30, target 1's ψ of 1e30 ahead of it) and a scaled backward entry
  // (2e-300, target 3's 1e300 behind it) underflows, and without the bound the permanent gave
  // target 2 a missed-detection probability of 0.994 against the exact 0.497.
  SingleScanProblem problem;
  problem.psi = RowMatrix(3, 3);
  problem.psi << 170, 1e30, 0,
                 1, 1e300, 0,
                 1, 1e300, 0;
  const SolveResult result = run_solver(*make_single_scan_solver("permanent"), problem);
  CHECK(result.report.skipped == "numerical");
  // k-best JPDA keeps the events' weights relative to the best one: no underflow.
  const SolveResult kept = run_solver(*make_single_scan_solver("kbest-jpda:k=100"), problem);
  REQUIRE(kept.report.skipped.empty());
  CHECK(kept.marginals(1, 0) == Approx(kept.marginals(2, 0)).epsilon(1e-12));
}

}  // namespace DABENCH_TEST_FILE
