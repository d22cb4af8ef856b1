// Tests of `lmipda` (LMIPDA of Musicki & La Scala 2008 in the ψ-only form of algorithms/single_scan/lmipda.hpp):
// closed forms (PDA for a lone track, a hand-computed 2x2 case, a symmetric case with huge
// weights), the published form written on likelihoods, clutter densities and P_G (shares no code
// with the algorithm), exactness on disjoint gates against brute force, and where Pd comes from.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "harness/core/errors.hpp"
#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"
#include "tests/support/pda_reference.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

SolveResult solve_with(const std::string& spec, const SingleScanProblem& problem) {
  auto solver = make_single_scan_solver(spec);
  return run_solver(*solver, problem);
}

RowMatrix solve_ok(const std::string& spec, const SingleScanProblem& problem) {
  const SolveResult result = solve_with(spec, problem);
  INFO("spec " << spec << ", skipped '" << result.report.skipped << "'");
  REQUIRE(result.report.skipped.empty());
  REQUIRE(result.marginals.rows() == problem.targets());
  REQUIRE(result.marginals.cols() == problem.measurements() + 1);
  return result.marginals;
}

SingleScanProblem with_pd(SingleScanProblem problem, double pd) {
  problem.context.pd = pd;
  return problem;
}

// LMIPDA as published, on the literal quantities: g(η, i) = p^η_i, the measurement likelihood
// restricted to η's gate (0 outside it), rho(i) = ρ_i the clutter density at measurement i:
//   P^η_i = Pd Pg (g_ηi/ρ_i) / Σ_j (g_ηj/ρ_j),  Ω^τ_i = ρ_i + Σ_{η≠τ} g_ηi P^η_i/(1 − P^η_i),
//   β^τ_i ∝ Pd Pg g_τi / Ω^τ_i,  β^τ_0 ∝ 1 − Pd Pg.
RowMatrix published_lmipda(const RowMatrix& g, const Vector& rho, double pd, double pg) {
  const Eigen::Index n = g.rows();
  const Eigen::Index m = g.cols();
  RowMatrix prior = RowMatrix::Zero(n, m);
  for (Eigen::Index eta = 0; eta < n; ++eta) {
    double denominator = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) denominator += g(eta, j) / rho[j];
    for (Eigen::Index i = 0; i < m; ++i) {
      if (g(eta, i) > 0.0) prior(eta, i) = pd * pg * (g(eta, i) / rho[i]) / denominator;
    }
  }
  RowMatrix beta = RowMatrix::Zero(n, m + 1);
  for (Eigen::Index tau = 0; tau < n; ++tau) {
    beta(tau, 0) = 1.0 - pd * pg;
    for (Eigen::Index i = 0; i < m; ++i) {
      double omega = rho[i];
      for (Eigen::Index eta = 0; eta < n; ++eta) {
        if (eta != tau) omega += g(eta, i) * prior(eta, i) / (1.0 - prior(eta, i));
      }
      beta(tau, i + 1) = pd * pg * g(tau, i) / omega;
    }
    beta.row(tau) /= beta.row(tau).sum();
  }
  return beta;
}

}  // namespace

TEST_CASE("lmipda: a lone track gets PDA (closed form)", "[lmipda]") {
  RandomStream rng(11, 0, 0);
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 1 + trial % 8;
    const Density density = trial % 3 == 0 ? Density::dense : trial % 3 == 1 ? Density::sparse : Density::extreme;
    const SingleScanProblem problem = random_problem(rng, 1, m, density, trial % 2 == 1);
    INFO("trial " << trial << "\npsi=\n" << problem.psi);
    const RowMatrix expected = pda_marginals(problem);
    // Pd cannot matter (no shared measurement): solved with or without it, the same numbers.
    CHECK(scaled_error(solve_ok("lmipda", problem), expected, 1e-14, 1e-300) <= 1.0);
    CHECK(scaled_error(solve_ok("lmipda", with_pd(problem, 0.3)), expected, 1e-14, 1e-300) <= 1.0);
    CHECK(scaled_error(solve_ok("lmipda:pd=0.9", problem), expected, 1e-14, 1e-300) <= 1.0);
  }
}

TEST_CASE("lmipda: hand-computed 2x2 with Pd 0.5", "[lmipda]") {
  // ψ = [[1, 2], [3, 4]], Pd = 0.5, so (1 − Pd)/Pd = 1.
  //   P^σ_j = Pd ψ_σj / Σ_j' ψ_σj':  target 1 (Σ = 3): P_11 = 1/6, P_12 = 1/3;
  //                                  target 2 (Σ = 7): P_21 = 3/14, P_22 = 2/7.
  //   c_σj = ψ_σj P/(1 − P):  c_11 = 1·(1/6)/(5/6) = 1/5,   c_12 = 2·(1/3)/(2/3) = 1,
  //                           c_21 = 3·(3/14)/(11/14) = 9/11, c_22 = 4·(2/7)/(5/7) = 8/5.
  //   Target 1: Ω_1/λ = 1 + c_21 = 20/11, Ω_2/λ = 1 + c_22 = 13/5;
  //             weights 1 : 1/(20/11) : 2/(13/5) = 1 : 11/20 : 10/13 = 260 : 143 : 200 (sum 603).
  //   Target 2: Ω_1/λ = 1 + c_11 = 6/5, Ω_2/λ = 1 + c_12 = 2;
  //             weights 1 : 3/(6/5) : 4/2 = 1 : 5/2 : 2 = 2 : 5 : 4 (sum 11).
  // (Exact marginals for comparison: [8, 5, 8]/21 and [4, 9, 8]/21.)
  SingleScanProblem problem;
  problem.psi = RowMatrix(2, 2);
  problem.psi << 1, 2, 3, 4;
  RowMatrix expected(2, 3);
  expected << 260.0 / 603, 143.0 / 603, 200.0 / 603, 2.0 / 11, 5.0 / 11, 4.0 / 11;
  CHECK(scaled_error(solve_ok("lmipda", with_pd(problem, 0.5)), expected, 1e-14, 0.0) <= 1.0);
  CHECK(scaled_error(solve_ok("lmipda:pd=0.5", problem), expected, 1e-14, 0.0) <= 1.0);
  // The same numbers from the published form with g = ψ, ρ = 1 (ψ = Pd g/(ρ(1 − Pd)) = g here).
  CHECK(scaled_error(published_lmipda(problem.psi, Vector::Ones(2), 0.5, 1.0), expected, 1e-14, 0.0) <= 1.0);
}

TEST_CASE("lmipda: psi-only form equals the published form with clutter density and P_G", "[lmipda]") {
  // Random likelihoods g (sparse), non-homogeneous clutter densities ρ_j, Pd and P_G; the problem
  // gets ψ_ηi = Pd N_ηi / (ρ_i (1 − Pd)) with N = P_G g (eq 11, r = 1), and the algorithm must
  // reproduce the published weights without ever seeing ρ.
  RandomStream rng(12, 0, 0);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 5;
    const int m = 1 + (trial / 5) % 6;
    const double pd = rng.uniform(0.05, 0.95);
    // P_G goes into the SPEC as text: round it to what the text says first.
    const double pg = std::stod(std::to_string(trial % 3 == 0 ? 1.0 : trial % 3 == 1 ? 0.9999 : rng.uniform(0.5, 1.0)));
    RowMatrix g = RowMatrix::Zero(n, m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) {
        if (rng.bernoulli(0.7)) g(i, j) = std::exp(rng.uniform(-4.0, 4.0));
      }
    }
    Vector rho(m);
    for (int j = 0; j < m; ++j) rho[j] = std::exp(rng.uniform(-3.0, 3.0));
    SingleScanProblem problem;
    problem.psi = RowMatrix(n, m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) problem.psi(i, j) = pd * pg * g(i, j) / (rho[j] * (1.0 - pd));
    }
    const std::string spec = "lmipda:pg=" + std::to_string(pg);
    const RowMatrix expected = published_lmipda(g, rho, pd, pg);
    INFO("trial " << trial << " pd " << pd << " pg " << pg << "\npsi=\n" << problem.psi);
    CHECK(scaled_error(solve_ok(spec, with_pd(problem, pd)), expected, 1e-12, 1e-300) <= 1.0);
    ++compared;
  }
  CHECK(compared == 200);
}

TEST_CASE("lmipda: P_G below one on a lone track scales the detection weights", "[lmipda]") {
  // One track: Ω = ρ, so β_j/β_0 = ψ_j (1 − Pd)/(1 − Pd Pg). Pd = 0.6, Pg = 0.5:
  // factor 0.4/0.7 = 4/7; ψ = [7/4, 7/2] gives weights 1 : 1 : 2, p = [1, 1, 2]/4.
  SingleScanProblem problem;
  problem.psi = RowMatrix(1, 2);
  problem.psi << 7.0 / 4, 7.0 / 2;
  RowMatrix expected(1, 3);
  expected << 0.25, 0.25, 0.5;
  CHECK(scaled_error(solve_ok("lmipda:pg=0.5,pd=0.6", problem), expected, 1e-14, 0.0) <= 1.0);
  // P_G < 1 makes Pd matter even for a lone track.
  CHECK(solve_with("lmipda:pg=0.5", problem).report.skipped == "needs_pd");
}

TEST_CASE("lmipda: disjoint gates give PDA per target and the exact marginals", "[lmipda]") {
  RandomStream rng(13, 0, 0);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 1 + trial % 6;
    const int m = trial % 7;
    const SingleScanProblem problem = disjoint_problem(rng, n, m);
    INFO("trial " << trial << "\npsi=\n" << problem.psi);
    const RowMatrix pda = pda_marginals(problem);
    const RowMatrix exact = brute_force_marginals(problem).marginals;
    CHECK(scaled_error(pda, exact, 1e-12, 1e-300) <= 1.0);  // the premise
    const RowMatrix without_pd = solve_ok("lmipda", problem);
    CHECK(scaled_error(without_pd, pda, 1e-14, 1e-300) <= 1.0);
    CHECK(scaled_error(without_pd, exact, 1e-12, 1e-300) <= 1.0);
    CHECK(scaled_error(solve_ok("lmipda", with_pd(problem, 0.6)), pda, 1e-14, 1e-300) <= 1.0);
  }
  // Two targets, two measurements each, no overlap: PDA per target.
  SingleScanProblem two;
  two.psi = RowMatrix(2, 4);
  two.psi << 2, 0, 0.5, 0, 0, 3, 0, 1;
  RowMatrix expected(2, 5);
  expected << 1 / 3.5, 2 / 3.5, 0, 0.5 / 3.5, 0, 0.2, 0, 0.6, 0, 0.2;
  CHECK(scaled_error(solve_ok("lmipda:pd=0.9", two), expected, 1e-14, 0.0) <= 1.0);
}

TEST_CASE("lmipda: Pd from the problem context or the pd option", "[lmipda]") {
  RandomStream rng(14, 0, 0);
  const SingleScanProblem problem = random_problem(rng, 4, 5, Density::dense);
  const RowMatrix from_context = solve_ok("lmipda", with_pd(problem, 0.6));
  const RowMatrix from_option = solve_ok("lmipda:pd=0.6", problem);
  CHECK(max_abs_difference(from_context, from_option) == 0.0);
  // The option overrides the context.
  CHECK(max_abs_difference(solve_ok("lmipda:pd=0.6", with_pd(problem, 0.3)), from_option) == 0.0);
  // And Pd matters: a different Pd gives different marginals (shared measurements everywhere).
  const RowMatrix other = solve_ok("lmipda", with_pd(problem, 0.3));
  CHECK(max_abs_difference(other, from_context) > 1e-3);
  // At fixed ψ, the other tracks' share of Ω^τ_j/λ is (1 − Pd) ψ_σj q/(1 − Pd q) with
  // q = ψ_σj/Σ_j' ψ_σj' < 1, which decreases as Pd grows (derivative ∝ q − 1 < 0): larger Pd
  // means less modulated clutter, larger detection weights, and a smaller p_i0 for every track.
  for (int i = 0; i < problem.targets(); ++i) CHECK(from_context(i, 0) < other(i, 0));
}

TEST_CASE("lmipda: refuses with needs_pd when Pd is missing and matters", "[lmipda]") {
  SingleScanProblem problem;
  problem.psi = RowMatrix(2, 2);
  problem.psi << 1, 2, 3, 4;
  CHECK(solve_with("lmipda", problem).report.skipped == "needs_pd");
  for (const double bad : {0.0, 1.0, -0.5, 1.5, std::nan("")}) {
    INFO("context pd " << bad);
    CHECK(solve_with("lmipda", with_pd(problem, bad)).report.skipped == "needs_pd");
  }
  // The option rescues a problem with an unusable context Pd.
  CHECK(solve_with("lmipda:pd=0.5", with_pd(problem, 1.0)).report.skipped.empty());
  // Degenerate problems do not need Pd: every row is p_0 = 1.
  for (const auto& [n, m] : {std::pair{0, 3}, std::pair{3, 0}, std::pair{0, 0}, std::pair{3, 4}}) {
    SingleScanProblem empty;
    empty.psi = RowMatrix::Zero(n, m);
    RowMatrix expected = RowMatrix::Zero(n, m + 1);
    expected.col(0).setOnes();
    CHECK(max_abs_difference(solve_ok("lmipda", empty), expected) == 0.0);
  }
}

TEST_CASE("lmipda: options are validated", "[lmipda]") {
  CHECK_THROWS_AS(make_single_scan_solver("lmipda:pd=1"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("lmipda:pd=0"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("lmipda:pg=0"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("lmipda:pg=1.01"), InputError);
  CHECK_THROWS_AS(make_single_scan_solver("lmipda:lambda=1"), InputError);
  CHECK_NOTHROW(make_single_scan_solver("lmipda:pd=0.3,pg=0.9999"));
}

TEST_CASE("lmipda: huge weights stay finite (symmetric closed form)", "[lmipda]") {
  // ψ = t·ones(2,2), Pd = 0.5: P = 0.5·t/(2t) = 1/4, c = t·(1/4)/(3/4) = t/3, Ω/λ = 1 + t/3,
  // weight t/(1 + t/3) → 3 as t → ∞: p → [1, 3, 3]/7 (for t = 1e300, to double precision).
  // With t = 3: weight 3/2, p = [1, 1.5, 1.5]/4 = [0.25, 0.375, 0.375].
  for (const auto& [t, p0, pj] : {std::tuple{1e300, 1.0 / 7, 3.0 / 7}, std::tuple{3.0, 0.25, 0.375}}) {
    SingleScanProblem problem;
    problem.psi = RowMatrix::Constant(2, 2, t);
    RowMatrix expected(2, 3);
    expected << p0, pj, pj, p0, pj, pj;
    INFO("t = " << t);
    CHECK(scaled_error(solve_ok("lmipda:pd=0.5", problem), expected, 1e-14, 0.0) <= 1.0);
  }
}

TEST_CASE("lmipda: relabelling targets and measurements permutes the marginals", "[lmipda]") {
  RandomStream rng(15, 0, 0);
  for (int trial = 0; trial < 20; ++trial) {
    const SingleScanProblem problem = random_problem(rng, 5, 6, Density::sparse, trial % 2 == 1);
    const std::vector<int> rows = random_permutation(rng, 5);
    const std::vector<int> cols = random_permutation(rng, 6);
    const RowMatrix base = solve_ok("lmipda:pd=0.7", problem);
    const RowMatrix permuted = solve_ok("lmipda:pd=0.7", permute_problem(problem, rows, cols));
    RowMatrix expected(5, 7);
    for (int i = 0; i < 5; ++i) {
      expected(rows[i], 0) = base(i, 0);
      for (int j = 0; j < 6; ++j) expected(rows[i], cols[j] + 1) = base(i, j + 1);
    }
    CHECK(scaled_error(permuted, expected, 1e-13, 1e-300) <= 1.0);
  }
}

}  // namespace DABENCH_TEST_FILE
