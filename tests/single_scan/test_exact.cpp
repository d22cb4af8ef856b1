// Tests of the `exact` algorithm (enumeration of feasible association events per cluster of the
// gating graph, eqs 9-13 of Williams & Lau 2014) against hand-computed cases and against the
// brute-force oracle of tests/support/brute_force.hpp, which shares no code with it.
#include <catch2/catch.hpp>

#include <chrono>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

constexpr double kRelative = 1e-12;  // exact vs brute force: both sum positive terms only
constexpr double kAbsolute = 1e-15;

RowMatrix solve_exact(const SingleScanProblem& problem, const std::string& spec = "exact") {
  auto solver = make_single_scan_solver(spec);
  const SolveResult result = run_solver(*solver, problem);
  REQUIRE(result.report.skipped.empty());
  return result.marginals;
}

void check_against_brute_force(const SingleScanProblem& problem, const RowMatrix& marginals) {
  const BruteForceResult reference = brute_force_marginals(problem);
  REQUIRE(marginals.rows() == problem.targets());
  REQUIRE(marginals.cols() == problem.measurements() + 1);
  const double error = scaled_error(marginals, reference.marginals, kRelative, kAbsolute);
  INFO("n=" << problem.targets() << " m=" << problem.measurements() << "\npsi=\n" << problem.psi
            << "\nexact=\n" << marginals << "\nbrute force=\n" << reference.marginals);
  CHECK(error <= 1.0);
}

}  // namespace

TEST_CASE("exact: hand-computed 2x2", "[exact]") {
  // ψ = [[a, b], [c, d]] = [[1, 2], [3, 4]]. Events (a_1, a_2) and weights:
  //   (0,0): 1   (1,0): a = 1   (2,0): b = 2   (0,1): c = 3   (0,2): d = 4
  //   (1,2): a·d = 4   (2,1): b·c = 6          ((1,1), (2,2) are inconsistent)
  // Z = 1 + a + b + c + d + ad + bc = 21.
  // p(a_1 = 0) = (1 + c + d)/Z = 8/21,  p(a_1 = 1) = (a + ad)/Z = 5/21,  p(a_1 = 2) = (b + bc)/Z = 8/21
  // p(a_2 = 0) = (1 + a + b)/Z = 4/21,  p(a_2 = 1) = (c + bc)/Z = 9/21,  p(a_2 = 2) = (d + ad)/Z = 8/21
  const RowMatrix psi = psi_2x2();
  const RowMatrix expected = marginals_2x2();

  const SingleScanProblem problem = make_problem(psi);
  const BruteForceResult oracle = brute_force_marginals(problem);
  CHECK(oracle.partition == Approx(21.0).epsilon(1e-15));
  CHECK(oracle.events == 7);
  CHECK(scaled_error(oracle.marginals, expected, 1e-14, 0.0) <= 1.0);
  CHECK(scaled_error(solve_exact(problem), expected, 1e-14, 0.0) <= 1.0);
}

TEST_CASE("exact: hand-computed 2x2 with missed-detection and clutter weights", "[exact]") {
  // General form: w(a) = Π_i w(i, a_i) Π_{j unused} w_0j with
  //   w = [[1, 2], [3, 4]],  w_10 = 2, w_20 = 1,  w_01 = 1, w_02 = 3.
  //   (0,0): w10·w20·w01·w02 = 2·1·1·3 = 6      (1,0): w11·w20·w02 = 1·1·3 = 3
  //   (2,0): w12·w20·w01 = 2·1·1 = 2            (0,1): w10·w21·w02 = 2·3·3 = 18
  //   (0,2): w10·w22·w01 = 2·4·1 = 8            (1,2): w11·w22 = 4      (2,1): w12·w21 = 6
  // Z = 47.  Target 1: miss 6+18+8 = 32, meas 1: 3+4 = 7, meas 2: 2+6 = 8.
  //          Target 2: miss 6+3+2 = 11, meas 1: 18+6 = 24, meas 2: 8+4 = 12.
  SingleScanProblem problem;
  problem.psi = RowMatrix(2, 2);
  problem.psi << 1, 2, 3, 4;
  problem.miss_weight = Vector(2);
  problem.miss_weight << 2, 1;
  problem.clutter_weight = Vector(2);
  problem.clutter_weight << 1, 3;
  REQUIRE(problem.validate().empty());
  RowMatrix expected(2, 3);
  expected << 32, 7, 8, 11, 24, 12;
  expected /= 47.0;

  const BruteForceResult oracle = brute_force_marginals(problem);
  CHECK(oracle.partition == Approx(47.0).epsilon(1e-15));
  CHECK(scaled_error(oracle.marginals, expected, 1e-14, 0.0) <= 1.0);
  CHECK(scaled_error(solve_exact(problem), expected, 1e-14, 0.0) <= 1.0);
}

TEST_CASE("exact: hand-computed 3x3 complete graphs", "[exact]") {
  // ψ = t·ones(3,3). Events with k assignments: C(3,k)^2 k! of them, weight t^k:
  //   Z = 1 + 9t + 18t² + 6t³.
  // Target 1 missed: the other two targets match into 3 measurements: 1 + 6t + 6t².
  // Target 1 on measurement j: t · (two targets into the two remaining measurements)
  //   = t(1 + 4t + 2t²).
  // t = 1: Z = 34, p = [13, 7, 7, 7]/34.   t = 2: Z = 139, p = [37, 34, 34, 34]/139.
  for (const auto& [t, miss, hit, z] : {std::tuple{1.0, 13.0, 7.0, 34.0}, std::tuple{2.0, 37.0, 34.0, 139.0}}) {
    const SingleScanProblem problem = make_problem(RowMatrix::Constant(3, 3, t));
    RowMatrix expected(3, 4);
    for (int i = 0; i < 3; ++i) expected.row(i) << miss / z, hit / z, hit / z, hit / z;
    const BruteForceResult oracle = brute_force_marginals(problem);
    CHECK(oracle.partition == Approx(z).epsilon(1e-15));
    CHECK(oracle.positive_events == 34);
    CHECK(scaled_error(oracle.marginals, expected, 1e-14, 0.0) <= 1.0);
    CHECK(scaled_error(solve_exact(problem), expected, 1e-14, 0.0) <= 1.0);
  }
}

TEST_CASE("exact: hand-computed 3x3 with two clusters", "[exact]") {
  // ψ = [[2, 1, 0], [1, 0, 0], [0, 0, 3]]: clusters {T1, T2, M1, M2} and {T3, M3}.
  // Cluster 1 events (a_1, a_2): (0,0): 1, (1,0): 2, (2,0): 1, (0,1): 1, (2,1): 1·1 = 1 → Z₁ = 6.
  //   p_1 = [1+1, 2, 1+1, 0]/6 = [2, 2, 2, 0]/6,  p_2 = [1+2+1, 1+1, 0, 0]/6 = [4, 2, 0, 0]/6.
  // Cluster 2: p_3 = [1, 0, 0, 3]/4.  Overall Z = 6·4 = 24.
  RowMatrix psi(3, 3);
  psi << 2, 1, 0, 1, 0, 0, 0, 0, 3;
  RowMatrix expected(3, 4);
  expected << 2.0 / 6, 2.0 / 6, 2.0 / 6, 0, 4.0 / 6, 2.0 / 6, 0, 0, 0.25, 0, 0, 0.75;
  const SingleScanProblem problem = make_problem(psi);
  const BruteForceResult oracle = brute_force_marginals(problem);
  CHECK(oracle.partition == Approx(24.0).epsilon(1e-15));
  CHECK(scaled_error(oracle.marginals, expected, 1e-14, 0.0) <= 1.0);
  const RowMatrix exact = solve_exact(problem);
  CHECK(scaled_error(exact, expected, 1e-14, 0.0) <= 1.0);
  // Gated-out pairs are exactly impossible.
  CHECK(exact(0, 3) == 0.0);
  CHECK(exact(1, 2) == 0.0);
  CHECK(exact(1, 3) == 0.0);
  CHECK(exact(2, 1) == 0.0);
  CHECK(exact(2, 2) == 0.0);
}

TEST_CASE("exact: matches brute force on random problems up to 6x6", "[exact]") {
  RandomStream rng(20240601, 1, 0);
  auto solver = make_single_scan_solver("exact");
  int checked = 0;
  for (int trial = 0; trial < 360; ++trial) {
    const auto [n, m, density, side, problem] = sweep_trial(rng, trial, 6);
    REQUIRE(problem.validate().empty());
    const SolveResult result = run_solver(*solver, problem);  // one solver: workspace reuse too
    INFO("trial " << trial << " density " << density_name(density) << " side weights " << side);
    REQUIRE(result.report.skipped.empty());
    check_against_brute_force(problem, result.marginals);
    ++checked;
  }
  CHECK(checked == 360);
}

TEST_CASE("exact: degenerate problems", "[exact]") {
  RandomStream rng(7, 2, 0);
  SECTION("no targets") {
    const RowMatrix m = solve_exact(make_problem(RowMatrix::Zero(0, 4)));
    CHECK(m.rows() == 0);
    CHECK(m.cols() == 5);
  }
  SECTION("no targets, no measurements") {
    const RowMatrix m = solve_exact(make_problem(RowMatrix::Zero(0, 0)));
    CHECK(m.rows() == 0);
    CHECK(m.cols() == 1);
  }
  SECTION("no measurements: every target is missed with probability 1") {
    const RowMatrix m = solve_exact(make_problem(RowMatrix::Zero(3, 0)));
    REQUIRE(m.rows() == 3);
    REQUIRE(m.cols() == 1);
    for (int i = 0; i < 3; ++i) CHECK(m(i, 0) == 1.0);
  }
  SECTION("all weights zero") {
    const RowMatrix m = solve_exact(make_problem(RowMatrix::Zero(4, 5)));
    REQUIRE(m.rows() == 4);
    REQUIRE(m.cols() == 6);
    for (int i = 0; i < 4; ++i) {
      CHECK(m(i, 0) == 1.0);
      for (int j = 1; j <= 5; ++j) CHECK(m(i, j) == 0.0);
    }
  }
  SECTION("all weights zero with side weights") {
    SingleScanProblem problem = make_problem(RowMatrix::Zero(2, 3));
    problem.miss_weight = Vector::Constant(2, 0.25);
    problem.clutter_weight = Vector::Constant(3, 7.0);
    const RowMatrix m = solve_exact(problem);
    for (int i = 0; i < 2; ++i) {
      CHECK(m(i, 0) == Approx(1.0).epsilon(1e-15));
      for (int j = 1; j <= 3; ++j) CHECK(m(i, j) == 0.0);
    }
  }
  SECTION("one huge weight dominates") {
    SingleScanProblem problem = random_problem(rng, 4, 4, Density::dense);
    problem.psi(1, 2) = 1e6;
    const RowMatrix m = solve_exact(problem);
    check_against_brute_force(problem, m);
    CHECK(m(1, 3) > 0.999);
  }
  SECTION("huge and tiny weights together") {
    SingleScanProblem problem = random_problem(rng, 5, 5, Density::dense);
    problem.psi(0, 0) = 1e6;
    problem.psi(1, 0) = 1e6;
    problem.psi(2, 4) = 1e-8;
    problem.psi(3, 3) = 1e-8;
    problem.psi(4, 1) = 1e6;
    check_against_brute_force(problem, solve_exact(problem));
  }
  SECTION("side weights not 1, with zero weights") {
    SingleScanProblem problem = random_problem(rng, 5, 4, Density::sparse, true);
    check_against_brute_force(problem, solve_exact(problem));
  }
  SECTION("single target, single measurement") {
    // p(a_1 = 1) = ψ/(1 + ψ); with w_10 = 4, w_01 = 0.5: ψ = 3/(4·0.5) = 1.5 → 0.6.
    SingleScanProblem problem = make_problem(RowMatrix::Constant(1, 1, 3.0));
    problem.miss_weight = Vector::Constant(1, 4.0);
    problem.clutter_weight = Vector::Constant(1, 0.5);
    const RowMatrix m = solve_exact(problem);
    CHECK(m(0, 1) == Approx(0.6).epsilon(1e-15));
    CHECK(m(0, 0) == Approx(0.4).epsilon(1e-15));
  }
}

TEST_CASE("exact: invariant to permuting targets and measurements", "[exact]") {
  RandomStream rng(99, 3, 0);
  auto solver = make_single_scan_solver("exact");
  for (int trial = 0; trial < 100; ++trial) {
    const int n = uniform_int(rng, 1, 6);
    const int m = uniform_int(rng, 1, 6);
    const Density density = trial % 2 == 0 ? Density::dense : Density::extreme;
    const SingleScanProblem problem = random_problem(rng, n, m, density, trial % 3 == 0);
    const std::vector<int> rows = random_permutation(rng, n);
    const std::vector<int> cols = random_permutation(rng, m);
    const SingleScanProblem permuted = permute_problem(problem, rows, cols);

    const RowMatrix base = run_solver(*solver, problem).marginals;
    const RowMatrix moved = run_solver(*solver, permuted).marginals;
    const RowMatrix moved_back = unpermute_marginals(moved, rows, cols);
    INFO("trial " << trial);
    CHECK(scaled_error(moved_back, base, kRelative, kAbsolute) <= 1.0);
  }
}

TEST_CASE("exact: threshold option zeroes small weights first", "[exact]") {
  RandomStream rng(5, 4, 0);
  const double threshold = 0.5;  // dense weights are exp(U(-3,3)): about 38% fall below
  auto solver = make_single_scan_solver("exact:threshold=0.5");
  for (int trial = 0; trial < 100; ++trial) {
    const int n = uniform_int(rng, 1, 6);
    const int m = uniform_int(rng, 1, 6);
    const SingleScanProblem problem = random_problem(rng, n, m, trial % 2 == 0 ? Density::dense : Density::extreme);
    SingleScanProblem thresholded = problem;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) {
        if (thresholded.psi(i, j) < threshold) thresholded.psi(i, j) = 0.0;
      }
    }
    const SolveResult result = run_solver(*solver, problem);
    REQUIRE(result.report.skipped.empty());
    INFO("trial " << trial);
    check_against_brute_force(thresholded, result.marginals);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) {
        if (problem.psi(i, j) < threshold) CHECK(result.marginals(i, j + 1) == 0.0);
      }
    }
  }
  // A weight exactly at the threshold is kept ("below it" are zeroed).
  const SingleScanProblem at = make_problem(RowMatrix::Constant(1, 1, 0.5));
  CHECK(solve_exact(at, "exact:threshold=0.5")(0, 1) == Approx(1.0 / 3.0).epsilon(1e-15));
}

TEST_CASE("exact: many clusters beyond brute-force size", "[exact]") {
  // 24×24 block-diagonal with six dense 4×4 blocks, rows and columns then shuffled: the
  // clusters are independent, so each block's marginals are those of the block alone.
  RandomStream rng(11, 5, 0);
  const int blocks = 6, size = 4, n = blocks * size;
  std::vector<SingleScanProblem> parts;
  SingleScanProblem problem = make_problem(RowMatrix::Zero(n, n));
  for (int b = 0; b < blocks; ++b) {
    parts.push_back(random_problem(rng, size, size, b % 2 == 0 ? Density::dense : Density::extreme));
    problem.psi.block(b * size, b * size, size, size) = parts.back().psi;
  }
  const std::vector<int> rows = random_permutation(rng, n);
  const std::vector<int> cols = random_permutation(rng, n);
  const SingleScanProblem shuffled = permute_problem(problem, rows, cols);
  const RowMatrix m = solve_exact(shuffled);
  REQUIRE(m.rows() == n);
  REQUIRE(m.cols() == n + 1);
  for (int b = 0; b < blocks; ++b) {
    const BruteForceResult reference = brute_force_marginals(parts[b]);
    for (int r = 0; r < size; ++r) {
      const int i = rows[b * size + r];
      INFO("block " << b << " row " << r);
      CHECK(m(i, 0) == Approx(reference.marginals(r, 0)).epsilon(kRelative).margin(kAbsolute));
      for (int c = 0; c < n; ++c) {
        const bool in_block = c >= b * size && c < (b + 1) * size;
        const double expected = in_block ? reference.marginals(r, c - b * size + 1) : 0.0;
        if (in_block) {
          CHECK(m(i, cols[c] + 1) == Approx(expected).epsilon(kRelative).margin(kAbsolute));
        } else {
          CHECK(m(i, cols[c] + 1) == 0.0);
        }
      }
    }
  }
}

TEST_CASE("exact: work limit refuses instead of hanging", "[exact]") {
  // A dense 12×12 problem has Σ_k C(12,k)² k! ≈ 1.2e10 feasible events.
  const SingleScanProblem big = make_problem(RowMatrix::Constant(12, 12, 1.0));
  auto solver = make_single_scan_solver("exact:max_events=1000");
  const auto start = std::chrono::steady_clock::now();
  const SolveResult result = run_solver(*solver, big);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK_FALSE(result.report.skipped.empty());
  CHECK(seconds < 5.0);  // hang guard only (≈ microseconds expected), not a performance claim

  // The same solver object then solves a small problem normally (no stale work counter).
  const SingleScanProblem small = make_problem(RowMatrix::Constant(3, 3, 1.0));
  const SolveResult after = run_solver(*solver, small);
  REQUIRE(after.report.skipped.empty());
  CHECK(after.marginals(0, 0) == Approx(13.0 / 34.0).epsilon(1e-14));

  // The limit counts feasible events: the complete 3×3 problem has exactly 34.
  CHECK(run_solver(*make_single_scan_solver("exact:max_events=34"), small).report.skipped.empty());
  CHECK_FALSE(run_solver(*make_single_scan_solver("exact:max_events=10"), small).report.skipped.empty());
}

}  // namespace DABENCH_TEST_FILE
