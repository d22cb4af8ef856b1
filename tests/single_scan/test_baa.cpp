// Tests of `baa` (the Bakhtiar–Alavi–Amoozegar approximation, algorithms/single_scan/baa.hpp): exact for one
// and two targets (closed form; brute force on random 2×m problems), exact on disjoint gates,
// hand-computed three-target cases where it is and is not exact, huge weights, relabelling.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"
#include "tests/support/pda_reference.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

RowMatrix solve_baa(const SingleScanProblem& problem) {
  auto solver = make_single_scan_solver("baa");
  const SolveResult result = run_solver(*solver, problem);
  REQUIRE(result.report.skipped.empty());
  REQUIRE(result.marginals.rows() == problem.targets());
  REQUIRE(result.marginals.cols() == problem.measurements() + 1);
  return result.marginals;
}

}  // namespace

TEST_CASE("baa: a lone target gets PDA (closed form)", "[baa]") {
  RandomStream rng(21, 0, 0);
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 1 + trial % 8;
    const Density density = trial % 3 == 0 ? Density::dense : trial % 3 == 1 ? Density::sparse : Density::extreme;
    const SingleScanProblem problem = random_problem(rng, 1, m, density, trial % 2 == 1);
    INFO("trial " << trial << "\npsi=\n" << problem.psi);
    CHECK(scaled_error(solve_baa(problem), pda_marginals(problem), 1e-14, 1e-300) <= 1.0);
  }
}

TEST_CASE("baa: exact for two targets (brute force on random 2 x m problems)", "[baa]") {
  // p(a_1 = j) ∝ ψ_1(j)(S_2 − ψ_2(j)), p(a_1 = 0) ∝ S_2 is the exact two-target marginal, so BAA
  // must agree with enumeration to rounding, for any density and with side weights.
  RandomStream rng(22, 0, 0);
  int compared = 0;
  for (int trial = 0; trial < 360; ++trial) {
    const int m = 1 + trial % 7;
    const Density density = (trial / 7) % 3 == 0 ? Density::dense : (trial / 7) % 3 == 1 ? Density::sparse : Density::extreme;
    const SingleScanProblem problem = random_problem(rng, 2, m, density, (trial / 21) % 2 == 1);
    const RowMatrix reference = brute_force_marginals(problem).marginals;
    INFO("trial " << trial << " (" << density_name(density) << ")\npsi=\n" << problem.psi << "\nbrute force=\n" << reference);
    CHECK(scaled_error(solve_baa(problem), reference, 1e-12, 1e-300) <= 1.0);
    ++compared;
  }
  CHECK(compared >= 300);
}

TEST_CASE("baa: hand-computed 2x2 is exact", "[baa]") {
  // S_1 = 4, S_2 = 8. Target 1: [S_2, 1·(S_2 − 3), 2·(S_2 − 4)] = [8, 5, 8] (/21).
  // Target 2: [S_1, 3·(S_1 − 1), 4·(S_1 − 2)] = [4, 9, 8] (/21): the exact marginals.
  const RowMatrix psi = psi_2x2();
  const RowMatrix expected = marginals_2x2();
  CHECK(scaled_error(solve_baa(make_problem(psi)), expected, 1e-14, 0.0) <= 1.0);
}

TEST_CASE("baa: hand-computed 3x3 complete graphs (not exact)", "[baa]") {
  // ψ = t·ones(3,3): S = 1 + 3t, f = (S − t)/S, β_j/β_0 = t f², p = [1, w, w, w]/(1 + 3w), w = t f².
  //   t = 1: f = 3/4, w = 9/16, p = [16, 9, 9, 9]/43   (exact: [13, 7, 7, 7]/34)
  //   t = 2: f = 5/7, w = 50/49, p = [49, 50, 50, 50]/199   (exact: [37, 34, 34, 34]/139)
  for (const auto& [t, miss, hit, z] : {std::tuple{1.0, 16.0, 9.0, 43.0}, std::tuple{2.0, 49.0, 50.0, 199.0}}) {
    RowMatrix expected(3, 4);
    for (int i = 0; i < 3; ++i) expected.row(i) << miss / z, hit / z, hit / z, hit / z;
    INFO("t = " << t);
    CHECK(scaled_error(solve_baa(make_problem(RowMatrix::Constant(3, 3, t))), expected, 1e-14, 0.0) <= 1.0);
  }
}

TEST_CASE("baa: hand-computed 3-target chain (middle target exact, ends not)", "[baa]") {
  // ψ = [[1, 2], [3, 0], [0, 4]]: T2 – M1 – T1 – M2 – T3. S = [4, 4, 5].
  // f_ij = (S_i − ψ_ij)/S_i: f_11 = 3/4, f_12 = 1/2, f_21 = 1/4, f_32 = 1/5.
  //   T1: [1, 1·f_21, 2·f_32] = [1, 1/4, 2/5] → [20, 5, 8]/33
  //   T2: [1, 3·f_11]         = [1, 9/4]      → [4, 9]/13
  //   T3: [1, 4·f_12]         = [1, 2]        → [1, 2]/3
  // Exact (8 events (a_1, a_2, a_3) with weights (0,0,0) 1, (1,0,0) 1, (2,0,0) 2, (0,1,0) 3,
  // (0,0,2) 4, (1,0,2) 1·4, (2,1,0) 2·3, (0,1,2) 3·4; Z = 33): T1 [20, 5, 8]/33, T2 [12, 21]/33,
  // T3 [13, 20]/33 → BAA is exact for T1 (its two neighbours do not interact) but not for T2, T3.
  RowMatrix psi(3, 2);
  psi << 1, 2, 3, 0, 0, 4;
  RowMatrix expected(3, 3);
  expected << 20.0 / 33, 5.0 / 33, 8.0 / 33, 4.0 / 13, 9.0 / 13, 0, 1.0 / 3, 0, 2.0 / 3;
  const RowMatrix baa = solve_baa(make_problem(psi));
  CHECK(scaled_error(baa, expected, 1e-14, 0.0) <= 1.0);
  const RowMatrix exact = brute_force_marginals(make_problem(psi)).marginals;
  CHECK(exact(0, 0) == Approx(20.0 / 33).epsilon(1e-14));
  CHECK(exact(1, 1) == Approx(21.0 / 33).epsilon(1e-14));
  CHECK(exact(2, 2) == Approx(20.0 / 33).epsilon(1e-14));
  CHECK(scaled_error(baa.row(0), exact.row(0), 1e-14, 0.0) <= 1.0);
}

TEST_CASE("baa: disjoint gates give the exact marginals", "[baa]") {
  RandomStream rng(23, 0, 0);
  for (int trial = 0; trial < 100; ++trial) {
    const SingleScanProblem problem = disjoint_problem(rng, 1 + trial % 6, trial % 7);
    INFO("trial " << trial << "\npsi=\n" << problem.psi);
    const RowMatrix baa = solve_baa(problem);
    CHECK(scaled_error(baa, pda_marginals(problem), 1e-14, 1e-300) <= 1.0);
    CHECK(scaled_error(baa, brute_force_marginals(problem).marginals, 1e-12, 1e-300) <= 1.0);
  }
  // Two exact two-target clusters side by side: each keeps its exact marginals.
  RandomStream rng2(24, 0, 0);
  for (int trial = 0; trial < 30; ++trial) {
    const SingleScanProblem a = random_problem(rng2, 2, 3, Density::dense);
    const SingleScanProblem b = random_problem(rng2, 2, 2, Density::dense);
    SingleScanProblem both = make_problem(RowMatrix::Zero(4, 5));
    both.psi.block(0, 0, 2, 3) = a.psi;
    both.psi.block(2, 3, 2, 2) = b.psi;
    CHECK(scaled_error(solve_baa(both), brute_force_marginals(both).marginals, 1e-12, 1e-300) <= 1.0);
  }
}

TEST_CASE("baa: degenerate problems", "[baa]") {
  for (const auto& [n, m] : {std::pair{0, 3}, std::pair{3, 0}, std::pair{0, 0}, std::pair{3, 4}}) {
    RowMatrix expected = RowMatrix::Zero(n, m + 1);
    expected.col(0).setOnes();
    CHECK(max_abs_difference(solve_baa(make_problem(RowMatrix::Zero(n, m))), expected) == 0.0);
  }
}

TEST_CASE("baa: huge weights stay finite", "[baa]") {
  // ψ = t·ones(2,2) (exact for two targets): p_0 = (1 + 2t)/(1 + 4t + 2t²), p_j = (t + t²)/(...).
  // For t = 1e300 these are 1e-300 (to rounding) and 1/2; the weights' sums overflow a double
  // unless the rows are scaled.
  SingleScanProblem problem = make_problem(RowMatrix::Constant(2, 2, 1e300));
  const RowMatrix p = solve_baa(problem);
  for (int i = 0; i < 2; ++i) {
    CHECK(p(i, 0) == Approx(1e-300).epsilon(1e-12));
    CHECK(p(i, 1) == Approx(0.5).epsilon(1e-14));
    CHECK(p(i, 2) == Approx(0.5).epsilon(1e-14));
  }
  // A dominant weight next to tiny ones: S − ψ is formed without cancellation.
  RowMatrix psi(2, 3);
  psi << 1e15, 1e-3, 2e-3, 1, 1, 1;
  const SingleScanProblem skewed = make_problem(psi);
  CHECK(scaled_error(solve_baa(skewed), brute_force_marginals(skewed).marginals, 1e-12, 1e-300) <= 1.0);
}

TEST_CASE("baa: relabelling targets and measurements permutes the marginals", "[baa]") {
  RandomStream rng(25, 0, 0);
  for (int trial = 0; trial < 20; ++trial) {
    const SingleScanProblem problem = random_problem(rng, 5, 6, Density::sparse, trial % 2 == 1);
    const std::vector<int> rows = random_permutation(rng, 5);
    const std::vector<int> cols = random_permutation(rng, 6);
    const RowMatrix base = solve_baa(problem);
    const RowMatrix permuted = solve_baa(permute_problem(problem, rows, cols));
    RowMatrix expected(5, 7);
    for (int i = 0; i < 5; ++i) {
      expected(rows[i], 0) = base(i, 0);
      for (int j = 0; j < 6; ++j) expected(rows[i], cols[j] + 1) = base(i, j + 1);
    }
    CHECK(scaled_error(permuted, expected, 1e-13, 1e-300) <= 1.0);
  }
}

}  // namespace DABENCH_TEST_FILE
