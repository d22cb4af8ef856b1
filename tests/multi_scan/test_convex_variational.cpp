// Tests of Algorithm 2 (ConvexVariationalPdca) and the registered multiple-scan methods of
// multiscan-convex-variational (cv, cvs, cvh, cvsh, cvsh1, msbp):
//  - optimality: the primal point of the converged duals satisfies the KKT conditions of the
//    convex free energy (63) itself, checked by projecting its gradient onto the constraints
//    (56)-(58) — a direct check that shares no formula with Lemmas 5-6;
//  - a single scan reduces (63) to the single-scan problem (44)/(138) with
//    w^{i,j} = Σ_A ψ(A) ψ(A, j) (Appendix A-A, eq 116), solved by the fractional BP kernel;
//  - Theorem 3: reweighting with the factor modification (91) leaves the solution unchanged;
//  - MSBP is exact where the graph is a tree; all methods against the exact posterior;
//  - the belief stopping rule stops within its tolerance of the limit.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <string>

#include "algorithms/multi_scan/convex_variational.hpp"
#include "algorithms/single_scan/fractional_bp.hpp"
#include "tests/support/free_energy_kkt.hpp"
#include "tests/support/multi_scan.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

struct Coefficients {
  std::vector<double> gamma, beta;
};

// β_t' = β̃·K1_t' for the given γ (β̃ = 1 unless told), as the registered methods do.
Coefficients coefficients(KappaWeights weights, std::vector<double> gamma, double beta_tilde = 1.0) {
  Coefficients c{gamma, std::vector<double>(gamma.size())};
  for (std::size_t t = 0; t < gamma.size(); ++t) {
    c.beta[t] = beta_tilde * ConvexVariationalPdca::block_scale(weights, gamma, static_cast<int>(t));
  }
  return c;
}

PdcaSettings tight(KappaWeights weights) {
  PdcaSettings settings;
  settings.weights = weights;
  settings.tolerance = 1e-12;
  settings.max_sweeps = 20000;
  settings.kernel_tolerance = 1e-13;
  settings.kernel_max_iterations = 100000;
  return settings;
}

struct Solved {
  MultiScanBeliefs beliefs;
  ConvexVariationalPdca::Primal primal;
  SolveReport report;
};

Solved solve_all(const MultiScanProblem& problem, const Coefficients& c, const PdcaSettings& settings) {
  ConvexVariationalPdca pdca;
  pdca.start(problem);
  for (const ScanFactors& scan : problem.scans) pdca.append_scan(scan);
  pdca.reweight(c.gamma, c.beta);
  Solved solved;
  pdca.solve(settings, solved.report);
  pdca.write_beliefs(solved.beliefs);
  pdca.recover_primal(solved.primal);
  return solved;
}

// The KKT check of (63) at Algorithm 2's primal point, with q^{0,j} = 1 − Σ_i q^{i,j} (61).
double projected_gradient(const MultiScanProblem& problem, const ConvexVariationalPdca::Primal& primal,
                          const Coefficients& c) {
  FreeEnergyPoint point{primal.track, primal.pair, {}};
  for (int t = 0; t < problem.scan_count(); ++t) {
    Vector clutter = Vector::Ones(problem.scans[t].measurements);
    for (int i = 0; i < problem.tracks(); ++i) clutter -= primal.pair[t][i].colwise().sum().tail(clutter.size()).transpose();
    point.clutter.push_back(clutter);
  }
  return dabench::test::projected_gradient(problem, point, c.gamma, c.beta);
}

}  // namespace

TEST_CASE("cv: the converged point is a KKT point of the convex free energy (63)") {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem({3, 3, {2, 3, 2}, 0.0}, seed);
    const Coefficients c = coefficients(KappaWeights::kLemma4, {0.25, 0.25, 0.25});
    const Solved solved = solve_all(problem, c, tight(KappaWeights::kLemma4));
    INFO("seed " << seed << " sweeps " << solved.report.iterations);
    REQUIRE(solved.report.converged);
    CHECK(projected_gradient(problem, solved.primal, c) < 1e-8);
    for (int i = 0; i < problem.tracks(); ++i) {
      CHECK((solved.primal.track[i] - solved.beliefs.track[i]).cwiseAbs().maxCoeff() < 1e-10);
    }
  }
}

TEST_CASE("Algorithm 2: KKT point of (63) for unequal gammas and both weight choices") {
  const MultiScanProblem problem = random_multi_scan_problem({2, 3, {3, 2}, 0.0}, 21);
  for (KappaWeights weights : {KappaWeights::kLemma4, KappaWeights::kHeuristic}) {
    const Coefficients c = coefficients(weights, {0.7, 0.1}, 1.2);
    const Solved solved = solve_all(problem, c, tight(weights));
    INFO("heuristic " << (weights == KappaWeights::kHeuristic) << " sweeps " << solved.report.iterations);
    REQUIRE(solved.report.converged);
    CHECK(projected_gradient(problem, solved.primal, c) < 1e-8);
  }
}

TEST_CASE("msbp: converges to a stationary point of the Bethe free energy (55)") {
  const MultiScanProblem problem = random_multi_scan_problem({3, 2, {2, 2}, 0.0}, 8);
  const Coefficients c{{1.0, 1.0}, {1.0, 1.0}};
  const Solved solved = solve_all(problem, c, tight(KappaWeights::kHeuristic));
  REQUIRE(solved.report.converged);
  CHECK(projected_gradient(problem, solved.primal, c) < 1e-8);
}

TEST_CASE("cv on a single scan equals fractional BP on the reduced single-scan problem") {
  // One scan: (63) reduces to (138) with w^{i,j} = Σ_A ψ(A) ψ(A, j), α = 1, β, γ of the scan,
  // and q(A) = Σ_a q^{i,a} ψ(A) ψ(A, a) / w^{i,a} (eq 116). Algorithm 2 and both column-dual solvers.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem({3, 4, {3}, 0.2}, 40 + seed);
    for (const char* spec : {"cv:solver=pdca,tolerance=1e-12,belief_tolerance=0", "cv:solver=newton", "cv:solver=lbfgs"}) {
    INFO(spec);
    const MultiScanRun run = run_multi_scan(spec, problem);
    REQUIRE(run.report.skipped.empty());
    REQUIRE(run.report.converged);
    const int n = problem.tracks();
    const int m = problem.scans[0].measurements;
    RowMatrix w(n, m + 1);
    for (int i = 0; i < n; ++i) w.row(i) = problem.prior[i].transpose() * problem.scans[0].factor[i];
    FractionalBpOptions options;
    options.gamma = 0.5;  // γ = 1/(|S|+1)
    options.alpha = 1.0;
    options.beta = ConvexVariationalPdca::block_scale(KappaWeights::kLemma4, {0.5}, 0);  // β̃ = 1
    options.tolerance = 1e-13;
    FractionalBpKernel kernel;
    const Vector miss = w.col(0);
    const Vector no_clutter;
    REQUIRE(kernel.solve(w.rightCols(m), miss, no_clutter, options).converged);
    const RowMatrix expected = kernel.target_marginals();
    INFO("seed " << seed);
    CHECK((run.beliefs.association[0].view() - expected).cwiseAbs().maxCoeff() < 1e-9);
    for (int i = 0; i < n; ++i) {
      Vector q = Vector::Zero(problem.hypotheses(i));
      for (int a = 0; a <= m; ++a) {
        if (w(i, a) > 0.0) q += expected(i, a) / w(i, a) * problem.prior[i].cwiseProduct(problem.scans[0].factor[i].col(a));
      }
      CHECK((run.beliefs.track[i] - q).cwiseAbs().maxCoeff() < 1e-9);
    }
    }
  }
}

TEST_CASE("Theorem 3: reweighting with the factor modification (91) keeps the solution") {
  const MultiScanProblem problem = random_multi_scan_problem({3, 3, {2, 3}, 0.0}, 77);
  for (KappaWeights weights : {KappaWeights::kLemma4, KappaWeights::kHeuristic}) {
    const Coefficients before = coefficients(weights, {0.3, 0.4}, 1.0);
    const Coefficients after = coefficients(weights, {0.0, 0.6}, 1.4);
    ConvexVariationalPdca pdca;
    pdca.start(problem);
    for (const ScanFactors& scan : problem.scans) pdca.append_scan(scan);
    pdca.reweight(before.gamma, before.beta);
    SolveReport report;
    pdca.solve(tight(weights), report);
    MultiScanBeliefs first, second;
    pdca.write_beliefs(first);
    pdca.reweight(after.gamma, after.beta);  // modifies the factors by (91)
    pdca.solve(tight(weights), report);
    pdca.write_beliefs(second);
    REQUIRE(report.converged);
    INFO("heuristic " << (weights == KappaWeights::kHeuristic));
    CHECK(belief_difference(first, second) < 1e-8);
    // Without the modification the new coefficients do change the solution.
    const Solved unmodified = solve_all(problem, after, tight(weights));
    CHECK(belief_difference(first, unmodified.beliefs) > 1e-3);
  }
}

TEST_CASE("msbp is exact on tree-structured problems") {
  SECTION("one track") {
    const MultiScanProblem problem = random_multi_scan_problem({1, 4, {2, 3, 1}, 0.2}, 3);
    const MultiScanRun run = run_multi_scan("msbp:tolerance=1e-12,belief_tolerance=0", problem);
    REQUIRE(run.report.converged);
    CHECK(belief_difference(run.beliefs, brute_force_posterior(problem)) < 1e-9);
  }
  SECTION("tracks with disjoint measurements") {
    // Track i can only take measurement i of each scan: no measurement is shared.
    MultiScanProblem problem = random_multi_scan_problem({3, 2, {3, 3}, 0.0}, 4);
    for (ScanFactors& scan : problem.scans) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 1; j <= 3; ++j) {
          if (j != i + 1) scan.factor[i].col(j).setZero();
        }
      }
    }
    const MultiScanRun run = run_multi_scan("msbp:tolerance=1e-12,belief_tolerance=0", problem);
    REQUIRE(run.report.converged);
    CHECK(belief_difference(run.beliefs, brute_force_posterior(problem)) < 1e-9);
  }
}

TEST_CASE("one track with beta = gamma on every scan: the fractional free energy is exact") {
  // With one track q^{0,j} = 1 − q^{1,j}, so (63) = the exact Gibbs free energy
  // + Σ_t' (β_t' − γ_t') Σ_j (1 − q^{1,j}) log(1 − q^{1,j}): exact when β_t' = γ_t'.
  const MultiScanProblem problem = random_multi_scan_problem({1, 4, {2, 3, 2}, 0.2}, 12);
  const MultiScanBeliefs exact = brute_force_posterior(problem);
  const Coefficients lemma4{{0.3, 0.3, 0.3}, {0.3, 0.3, 0.3}};
  CHECK(belief_difference(solve_all(problem, lemma4, tight(KappaWeights::kLemma4)).beliefs, exact) < 1e-9);
  const Coefficients heuristic{{0.7, 0.7, 0.7}, {0.7, 0.7, 0.7}};
  CHECK(belief_difference(solve_all(problem, heuristic, tight(KappaWeights::kHeuristic)).beliefs, exact) < 1e-9);
  // β ≠ γ: the single-track term makes the beliefs differ (the methods' conservatism).
  const Coefficients cv = coefficients(KappaWeights::kLemma4, {0.25, 0.25, 0.25});
  CHECK(belief_difference(solve_all(problem, cv, tight(KappaWeights::kLemma4)).beliefs, exact) > 1e-3);
}

TEST_CASE("all methods against the exact posterior on weakly coupled problems") {
  // Three tracks, three scans; track i's likelihood for measurement j != i is scaled by 1e-4,
  // so the graph is nearly a tree: msbp is nearly exact. The convex methods keep the error of
  // their β_t' − γ_t' single-track terms (above): measured 4e-3 (cvs) to 7e-2 (cvh).
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    MultiScanProblem problem = random_multi_scan_problem({3, 3, {3, 3, 3}, 0.0}, seed);
    for (ScanFactors& scan : problem.scans) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 1; j <= 3; ++j) scan.factor[i].col(j) *= j == i + 1 ? 1.0 : 1e-4;
      }
    }
    const MultiScanRun exact = run_multi_scan("ms-exact", problem);
    REQUIRE(exact.report.skipped.empty());
    CHECK(belief_difference(exact.beliefs, brute_force_posterior(problem)) < 1e-12);
    const MultiScanRun msbp = run_multi_scan("msbp:tolerance=1e-12,belief_tolerance=0", problem);
    CHECK(belief_difference(msbp.beliefs, exact.beliefs) < 1e-7);
    for (const char* spec : {"cv", "cvs", "cvh", "cvsh", "cvsh1", "cvs:gamma=0.55"}) {
      const MultiScanRun run = run_multi_scan(spec, problem);
      INFO(spec << " seed " << seed);
      REQUIRE(run.report.skipped.empty());
      CHECK(belief_difference(run.beliefs, exact.beliefs) < 0.1);
    }
  }
}

TEST_CASE("the belief stopping rule stops early within its tolerance of the limit") {
  // The rule estimates the distance to the limit from the observed linear rate; compared with
  // the λ rule run to 1e-12, the beliefs must be within belief_tolerance (1e-7, margin 10×).
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem({3, 4, {3, 2, 3, 2}, 0.0}, seed);
    for (const std::string method : {"cv", "cvs"}) {
      INFO(method << " seed " << seed);
      const MultiScanRun limit =
          run_multi_scan(method + ":solver=pdca,tolerance=1e-12,belief_tolerance=0,max_sweeps=100000", problem);
      const MultiScanRun early = run_multi_scan(method + ":solver=pdca,belief_tolerance=1e-7", problem);
      REQUIRE(limit.report.converged);
      REQUIRE(early.report.converged);
      CHECK(early.report.iterations < limit.report.iterations);
      CHECK(belief_difference(early.beliefs, limit.beliefs) < 1e-6);
    }
  }
}

TEST_CASE("registered methods reject invalid options") {
  CHECK_THROWS_AS(make_multi_scan_solver("cv:belief_tolerance=-1"), InputError);
  CHECK_THROWS_AS(make_multi_scan_solver("cvs:gamma=1"), InputError);
  CHECK_THROWS_AS(make_multi_scan_solver("cvsh:gamma=1.5"), InputError);
  CHECK_THROWS_AS(make_multi_scan_solver("cv:beta_tilde=0.7"), InputError);
  CHECK_THROWS_AS(make_multi_scan_solver("msbp:max_sweeps=0"), InputError);
  CHECK_NOTHROW(make_multi_scan_solver("cvsh:gamma=1"));
}

}  // namespace DABENCH_TEST_FILE
