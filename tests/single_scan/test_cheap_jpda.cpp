// Tests of `cheap-jpda` and `modified-cheap-jpda` (algorithms/single_scan/cheap_jpda.hpp): the
// formulas evaluated densely in the test (every pair, as the Tracker Component Library writes
// them) against the sparse solver on random problems; hand-computed 2×2 values; a lone target gets
// exact PDA; the bias; bad options.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "harness/core/errors.hpp"
#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

RowMatrix solve_spec(const std::string& spec, const RowMatrix& psi) {
  SingleScanProblem problem;
  problem.psi = psi;
  auto solver = make_single_scan_solver(spec);
  const SolveResult result = run_solver(*solver, problem);
  REQUIRE(result.report.skipped.empty());
  return result.marginals;
}

// The dense formulas: S_i row sums, T_j column sums; Quan's column term Σ_k ψ_kj² / S_k.
RowMatrix dense_formula(const RowMatrix& psi, double bias, bool modified) {
  const Eigen::Index n = psi.rows(), m = psi.cols();
  RowMatrix beta = RowMatrix::Zero(n, m + 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s_i = psi.row(i).sum();
    double assigned = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      if (psi(i, j) == 0.0) continue;
      double column = 0.0;
      for (Eigen::Index k = 0; k < n; ++k) {
        if (k == i || psi(k, j) == 0.0) continue;
        column += modified ? psi(k, j) * psi(k, j) / psi.row(k).sum() : psi(k, j);
      }
      beta(i, j + 1) = psi(i, j) / (s_i + column + bias);
      assigned += beta(i, j + 1);
    }
    beta(i, 0) = 1.0 - assigned;
  }
  return beta;
}

}  // namespace

TEST_CASE("cheap jpda: the sparse solvers equal the dense formulas on random problems", "[cheap_jpda]") {
  RandomStream rng(31, 0, 0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + static_cast<int>(rng.uniform() * 6), m = static_cast<int>(rng.uniform() * 7);
    RowMatrix psi(n, m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) psi(i, j) = rng.uniform() < 0.35 ? 0.0 : -2.0 * std::log(1.0 - rng.uniform());
    }
    const double bias = trial % 3 == 0 ? 0.25 : 1.0;
    const std::string options = trial % 3 == 0 ? ":bias=0.25" : "";
    INFO("trial " << trial);
    CHECK((solve_spec("cheap-jpda" + options, psi) - dense_formula(psi, bias, false)).cwiseAbs().maxCoeff() < 1e-14);
    CHECK((solve_spec("modified-cheap-jpda" + options, psi) - dense_formula(psi, bias, true)).cwiseAbs().maxCoeff() <
          1e-14);
  }
}

TEST_CASE("cheap jpda: hand-computed 2 x 2 values", "[cheap_jpda]") {
  RowMatrix psi(2, 2);
  psi << 2, 1,
         1, 3;
  // S = (3, 4), T = (3, 4): β_11 = 2 / (3 + 1 + 1), β_12 = 1 / (3 + 3 + 1), β_21 = 1 / (4 + 2 + 1), β_22 = 3 / (4 + 1 + 1).
  const RowMatrix cheap = solve_spec("cheap-jpda", psi);
  CHECK(cheap(0, 1) == Approx(0.4).epsilon(1e-15));
  CHECK(cheap(0, 2) == Approx(1.0 / 7).epsilon(1e-15));
  CHECK(cheap(0, 0) == Approx(1 - 0.4 - 1.0 / 7).epsilon(1e-14));
  CHECK(cheap(1, 1) == Approx(1.0 / 7).epsilon(1e-15));
  CHECK(cheap(1, 2) == Approx(0.5).epsilon(1e-15));
  // Quan: r ψ terms ψ²/S = (4/3, 1/3; 1/4, 9/4): β_11 = 2 / (3 + 1/4 + 1), β_12 = 1 / (3 + 9/4 + 1),
  // β_21 = 1 / (4 + 4/3 + 1), β_22 = 3 / (4 + 1/3 + 1).
  const RowMatrix modified = solve_spec("modified-cheap-jpda", psi);
  CHECK(modified(0, 1) == Approx(2 / 4.25).epsilon(1e-15));
  CHECK(modified(0, 2) == Approx(1 / 6.25).epsilon(1e-15));
  CHECK(modified(1, 1) == Approx(1 / (5 + 4.0 / 3)).epsilon(1e-15));
  CHECK(modified(1, 2) == Approx(3 / (5 + 1.0 / 3)).epsilon(1e-15));
}

TEST_CASE("cheap jpda: a lone target gets PDA; bias 0 leaves no missed detection", "[cheap_jpda]") {
  RowMatrix psi(2, 4);
  psi << 2, 0.5, 0, 0,
         0, 0, 3, 1;  // no shared measurement
  SingleScanProblem problem;
  problem.psi = psi;
  const BruteForceResult exact = brute_force_marginals(problem);
  for (const char* spec : {"cheap-jpda", "modified-cheap-jpda"}) {
    CHECK((solve_spec(spec, psi) - exact.marginals).cwiseAbs().maxCoeff() < 1e-15);
  }
  const RowMatrix no_bias = solve_spec("cheap-jpda:bias=0", psi);
  CHECK(no_bias(0, 0) == 0.0);
  CHECK(no_bias(0, 1) == Approx(0.8));
  CHECK(no_bias(1, 4) == Approx(0.25));
}

TEST_CASE("cheap jpda: bad options and overflowing sums", "[cheap_jpda]") {
  CHECK_THROWS_AS(make_single_scan_solver("cheap-jpda:bias=-1"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("modified-cheap-jpda:bias=inf"), InputError);
  RowMatrix psi(2, 1);
  psi << 1e308, 1e308;
  SingleScanProblem problem;
  problem.psi = psi;
  auto solver = make_single_scan_solver("cheap-jpda");
  CHECK(run_solver(*solver, problem).report.skipped == "numerical");
}

}  // namespace DABENCH_TEST_FILE
