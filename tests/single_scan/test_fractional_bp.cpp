// Tests of `fbp` and FractionalBpKernel, Algorithm 1 of multiscan-convex-variational
// (Appendix D, eqs 138-165):
//  - γ = 1, α = β = 1 is BP (remark after eq 165): marginals equal `bp` run to δ = 1e-12, on
//    grid problems and on random problems with side weights;
//  - at convergence the KKT conditions (145)-(147) and primal feasibility (139)-(141) hold to
//    1e-8 for several (γ, α, β) with non-unit w_i0, w_0j;
//  - γ = 0, α = β = 1: (138) is entropy-regularised transport whose KKT solution has the scaling
//    form q_ij = e·w_ij a_i b_j, q_i0 = w_i0 a_i, q_0j = w_0j b_j; compared with a Sinkhorn
//    iteration written here;
//  - optimality: (138) at the solution is below (138) at random feasible perturbations (γ < 1),
//    and the reported objective is (138) recomputed here; γ = 1 on a tree gives −log Z (the
//    Bethe free energy is exact there), Z by brute force;
//  - zero weights stay exactly zero; bad parameters and weights are rejected by name;
//  - huge odds (a pair 1e20 or 1e200 times likelier than the rest) give finite, accurate
//    marginals: exact ones on a tree at γ = 1, the reduced problem's elsewhere.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "algorithms/single_scan/fractional_bp.hpp"
#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

std::vector<SingleScanProblem> grid_problems(int rows, int cols, double spacing, int count) {
  const auto scenario = single_scan_scenario_registry().find("grid")->create(
      {{"rows", std::to_string(rows)}, {"cols", std::to_string(cols)}, {"spacing", std::to_string(spacing)}});
  std::vector<SingleScanProblem> problems;
  ScenarioSample sample;
  for (int k = 0; k < count; ++k) {
    RandomStream rng(99, 0, static_cast<std::uint32_t>(k));
    scenario->generate(rng, sample);
    problems.push_back(sample.problem);
  }
  return problems;
}

// The full primal solution: Q(i, j) for i = 0..n, j = 0..m, Q(0, 0) unused (= 0).
struct Primal {
  RowMatrix q;
};

struct Weights {
  RowMatrix w;    // (n+1)×(m+1): w(i, j) = w_ij, w(i, 0) = w_i0, w(0, j) = w_0j, w(0, 0) unused
};

Weights full_weights(const SingleScanProblem& problem) {
  const int n = problem.targets(), m = problem.measurements();
  Weights out{RowMatrix::Zero(n + 1, m + 1)};
  for (int i = 1; i <= n; ++i) out.w(i, 0) = miss_weight_of(problem, i - 1);
  for (int j = 1; j <= m; ++j) out.w(0, j) = clutter_weight_of(problem, j - 1);
  out.w.bottomRightCorner(n, m) = problem.psi;
  return out;
}

struct KernelRun {
  Primal primal;
  FractionalBpOutcome outcome;
};

KernelRun run_kernel(FractionalBpKernel& kernel, const SingleScanProblem& problem, const FractionalBpOptions& options) {
  KernelRun run;
  run.outcome = kernel.solve(problem.psi, problem.miss_weight, problem.clutter_weight, options);
  const int n = problem.targets(), m = problem.measurements();
  run.primal.q = RowMatrix::Zero(n + 1, m + 1);
  run.primal.q.bottomRows(n) = kernel.target_marginals();
  run.primal.q.row(0).tail(m) = kernel.clutter_marginals().transpose();
  return run;
}

// Objective (138), written out independently of the kernel.
double objective_138(const Weights& weights, const RowMatrix& q, double gamma, double alpha, double beta) {
  const auto term = [](double x, double w) { return x > 0.0 ? x * std::log(x / w) : 0.0; };
  double total = 0.0;
  for (int i = 0; i < q.rows(); ++i) {
    for (int j = 0; j < q.cols(); ++j) {
      if (i == 0 && j == 0) continue;
      const double w = weights.w(i, j), x = q(i, j);
      if (i == 0) total += beta * term(x, w);
      else if (j == 0) total += alpha * term(x, w);
      else if (w > 0.0) total += term(x, w) - gamma * (x < 1.0 ? (1.0 - x) * std::log(1.0 - x) : 0.0);
    }
  }
  return total;
}

// Largest violation of eqs (139)-(141) and (145)-(147), with λ_i and μ_j recovered from (146)
// and (147); also requires q = 0 exactly where w_ij = 0.
struct KktResiduals {
  double stationarity = 0.0;  // eq (145)
  double rows = 0.0;          // eq (139)
  double columns = 0.0;       // eq (140)
  bool interior = true;       // 0 < q < 1 where w_ij > 0 (Lemma 7), q = 0 where w_ij = 0
};

KktResiduals kkt_residuals(const Weights& weights, const RowMatrix& q, double gamma, double alpha, double beta) {
  const int n = static_cast<int>(q.rows()) - 1, m = static_cast<int>(q.cols()) - 1;
  KktResiduals r;
  std::vector<double> lambda(n + 1), mu(m + 1);
  for (int i = 1; i <= n; ++i) lambda[i] = alpha * std::log(q(i, 0) / weights.w(i, 0)) + alpha;  // eq (146)
  for (int j = 1; j <= m; ++j) mu[j] = beta * std::log(q(0, j) / weights.w(0, j)) + beta;        // eq (147)
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= m; ++j) {
      if (i == 0 && j == 0) continue;
      const double w = weights.w(i, j), x = q(i, j);
      if (w == 0.0) {
        r.interior = r.interior && x == 0.0;
        continue;
      }
      // A target or measurement with no gated pair has q_i0 = 1 or q_0j = 1 exactly.
      const bool pair = i > 0 && j > 0;
      r.interior = r.interior && x > 0.0 && (pair ? x < 1.0 : x <= 1.0);
      if (pair) {
        const double residual = std::log(x / w) + gamma * std::log1p(-x) + 1.0 + gamma - lambda[i] - mu[j];
        r.stationarity = std::max(r.stationarity, std::fabs(residual));
      }
    }
  }
  for (int i = 1; i <= n; ++i) r.rows = std::max(r.rows, std::fabs(q.row(i).sum() - 1.0));
  for (int j = 1; j <= m; ++j) r.columns = std::max(r.columns, std::fabs(q.col(j).sum() - 1.0));
  return r;
}

FractionalBpOptions options_of(double gamma, double alpha, double beta) {
  FractionalBpOptions options;
  options.gamma = gamma;
  options.alpha = alpha;
  options.beta = beta;
  return options;
}

// Independent solution of (138) at γ = 0, α = β = 1 by Sinkhorn scaling: stationarity gives
// q_ij = w_ij e^{λ_i + μ_j − 1}, q_i0 = w_i0 e^{λ_i − 1}, q_0j = w_0j e^{μ_j − 1}; with
// a_i = e^{λ_i − 1}, b_j = e^{μ_j − 1}: q_ij = e·w_ij a_i b_j, and (139)-(140) become
// a_i = 1 / (w_i0 + e Σ_j w_ij b_j), b_j = 1 / (w_0j + e Σ_i w_ij a_i).
RowMatrix sinkhorn_solution(const Weights& weights) {
  const int n = static_cast<int>(weights.w.rows()) - 1, m = static_cast<int>(weights.w.cols()) - 1;
  const double e = std::exp(1.0);
  std::vector<double> a(n + 1, 1.0), b(m + 1, 1.0);
  for (int sweep = 0; sweep < 100000; ++sweep) {
    double change = 0.0;
    for (int i = 1; i <= n; ++i) {
      double s = weights.w(i, 0);
      for (int j = 1; j <= m; ++j) s += e * weights.w(i, j) * b[j];
      a[i] = 1.0 / s;
    }
    for (int j = 1; j <= m; ++j) {
      double s = weights.w(0, j);
      for (int i = 1; i <= n; ++i) s += e * weights.w(i, j) * a[i];
      change = std::max(change, std::fabs(std::log(b[j] * s)));
      b[j] = 1.0 / s;
    }
    if (change < 1e-15) break;
  }
  RowMatrix q = RowMatrix::Zero(n + 1, m + 1);
  for (int i = 1; i <= n; ++i) q(i, 0) = weights.w(i, 0) * a[i];
  for (int j = 1; j <= m; ++j) q(0, j) = weights.w(0, j) * b[j];
  for (int i = 1; i <= n; ++i) {
    for (int j = 1; j <= m; ++j) q(i, j) = e * weights.w(i, j) * a[i] * b[j];
  }
  return q;
}

std::vector<SingleScanProblem> side_weight_problems() {
  RandomStream rng(2024, 4, 0);
  std::vector<SingleScanProblem> problems;
  for (int k = 0; k < 6; ++k) {
    problems.push_back(random_problem(rng, 2 + k, 7 - k, Density::dense, true));
    problems.push_back(random_problem(rng, 3 + k, 4 + k, Density::sparse, true));
  }
  return problems;
}

}  // namespace

TEST_CASE("fbp: gamma 1 with alpha = beta = 1 equals bp on grid problems", "[fbp]") {
  auto fbp = make_single_scan_solver("fbp:tolerance=1e-12");
  auto bp = make_single_scan_solver("bp:delta=1e-12");
  struct Pool {
    int rows, cols;
    double spacing;
  };
  for (const Pool pool : {Pool{2, 3, 0.0}, Pool{2, 3, 2.0}, Pool{2, 3, 3.0}, Pool{3, 10, 3.0}}) {
    for (const SingleScanProblem& problem : grid_problems(pool.rows, pool.cols, pool.spacing, 20)) {
      INFO("grid " << pool.rows << "x" << pool.cols << " spacing " << pool.spacing << ", n " << problem.targets()
                   << ", m " << problem.measurements());
      const SolveResult a = run_solver(*fbp, problem);
      const SolveResult b = run_solver(*bp, problem);
      REQUIRE(a.report.converged);
      REQUIRE(b.report.converged);
      CHECK(max_abs_difference(a.marginals, b.marginals) < 1e-9);
      CHECK(std::isfinite(a.report.free_energy));
    }
  }
}

TEST_CASE("fbp: gamma 1 with alpha = beta = 1 equals bp with side weights", "[fbp]") {
  // bp solves the normalised ψ = w_ij/(w_i0 w_0j); at α = β = 1 this is the same energy (138)
  // up to a constant, so the marginals agree.
  auto fbp = make_single_scan_solver("fbp:tolerance=1e-12");
  auto bp = make_single_scan_solver("bp:delta=1e-12");
  for (const SingleScanProblem& problem : side_weight_problems()) {
    const SolveResult a = run_solver(*fbp, problem);
    const SolveResult b = run_solver(*bp, problem);
    REQUIRE(a.report.converged);
    CHECK(max_abs_difference(a.marginals, b.marginals) < 1e-9);
  }
}

TEST_CASE("fbp: KKT conditions 145-147 hold at convergence", "[fbp]") {
  struct Coefficients {
    double gamma, alpha, beta;
  };
  FractionalBpKernel kernel;  // reused across problems and coefficients
  for (const Coefficients c : {Coefficients{0.0, 1.0, 1.0}, Coefficients{0.5, 1.0, 1.0}, Coefficients{0.95, 1.0, 1.0},
                               Coefficients{0.5, 1.0, 0.6}, Coefficients{0.95, 1.0, 2.5}, Coefficients{0.3, 0.8, 1.5},
                               Coefficients{0.5, 0.7, 0.6}, Coefficients{1.0, 1.0, 1.0}}) {
    for (const SingleScanProblem& problem : side_weight_problems()) {
      INFO("gamma " << c.gamma << " alpha " << c.alpha << " beta " << c.beta << ", n " << problem.targets() << ", m "
                    << problem.measurements());
      const KernelRun run = run_kernel(kernel, problem, options_of(c.gamma, c.alpha, c.beta));
      REQUIRE(run.outcome.converged);
      const Weights weights = full_weights(problem);
      const KktResiduals r = kkt_residuals(weights, run.primal.q, c.gamma, c.alpha, c.beta);
      CHECK(r.interior);
      CHECK(r.stationarity < 1e-8);
      CHECK(r.rows < 1e-12);
      CHECK(r.columns < 1e-8);
      // The reported objective is (138) at the returned q.
      CHECK(run.outcome.objective ==
            Approx(objective_138(weights, run.primal.q, c.gamma, c.alpha, c.beta)).epsilon(0).margin(1e-12));
    }
  }
}

TEST_CASE("fbp: gamma 0 with alpha = beta = 1 equals the Sinkhorn scaling solution", "[fbp]") {
  FractionalBpKernel kernel;
  for (const SingleScanProblem& problem : side_weight_problems()) {
    const KernelRun run = run_kernel(kernel, problem, options_of(0.0, 1.0, 1.0));
    REQUIRE(run.outcome.converged);
    CHECK(max_abs_difference(run.primal.q, sinkhorn_solution(full_weights(problem))) < 1e-9);
  }
}

TEST_CASE("fbp: the solution minimises the objective over feasible perturbations", "[fbp]") {
  RandomStream rng(77, 1, 0);
  FractionalBpKernel kernel;
  const SingleScanProblem problem = random_problem(rng, 5, 6, Density::sparse, true);
  const Weights weights = full_weights(problem);
  const int n = problem.targets(), m = problem.measurements();
  for (const double gamma : {0.0, 0.5, 0.95}) {
    INFO("gamma " << gamma);
    const FractionalBpOptions options = options_of(gamma, 1.0, gamma > 0.9 ? 1.5 : 0.8);
    const KernelRun run = run_kernel(kernel, problem, options);
    REQUIRE(run.outcome.converged);
    const RowMatrix& q = run.primal.q;
    const double best = objective_138(weights, q, options.gamma, options.alpha, options.beta);
    int tried = 0;
    for (int k = 0; k < 2000; ++k) {
      // A feasible direction: a 4-cycle on pairs (i, j), i, j ≥ 1, or a 3-cycle through the
      // miss and clutter entries (i, j) + (i, 0) − (0, j) −; both keep (139)-(140).
      RowMatrix d = RowMatrix::Zero(n + 1, m + 1);
      const int i1 = uniform_int(rng, 1, n), j1 = uniform_int(rng, 1, m);
      if (rng.bernoulli(0.5)) {
        d(i1, j1) = 1.0, d(i1, 0) = -1.0, d(0, j1) = -1.0;
      } else {
        const int i2 = uniform_int(rng, 1, n), j2 = uniform_int(rng, 1, m);
        if (i1 == i2 || j1 == j2) continue;
        d(i1, j1) = 1.0, d(i2, j2) = 1.0, d(i1, j2) = -1.0, d(i2, j1) = -1.0;
      }
      bool supported = true;  // only pairs with w > 0 are variables
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= m; ++j) supported = supported && (d(i, j) == 0.0 || weights.w(i, j) > 0.0);
      }
      if (!supported) continue;
      const double step = rng.uniform(-1.0, 1.0) * 1e-3;
      const RowMatrix moved = q + step * d;
      bool inside = true;
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= m; ++j) inside = inside && (d(i, j) == 0.0 || (moved(i, j) > 0.0 && moved(i, j) < 1.0));
      }
      if (!inside) continue;
      ++tried;
      CHECK(objective_138(weights, moved, options.gamma, options.alpha, options.beta) > best);
    }
    CHECK(tried > 500);
    // The solution for another γ is feasible too, and worse under this γ's objective.
    const KernelRun other = run_kernel(kernel, problem, options_of(gamma == 0.5 ? 0.0 : 0.5, 1.0, 1.0));
    CHECK(objective_138(weights, other.primal.q, options.gamma, options.alpha, options.beta) > best);
  }
}

TEST_CASE("fbp: with gamma 1 on a tree the objective is -log Z", "[fbp]") {
  // On a forest the Bethe free energy (γ = α = β = 1) is exact: min (138) = −log Z (eq 12).
  RowMatrix psi(3, 4);
  psi << 0.7, 2.0, 0.0, 0.0,  //
      0.0, 1.5, 0.3, 0.0,     //
      0.0, 0.0, 0.0, 4.0;
  SingleScanProblem problem;
  problem.psi = psi;
  problem.miss_weight = Vector(3);
  problem.miss_weight << 0.5, 2.0, 1.2;
  problem.clutter_weight = Vector(4);
  problem.clutter_weight << 1.0, 0.3, 3.0, 0.8;
  const BruteForceResult exact = brute_force_marginals(problem);
  auto fbp = make_single_scan_solver("fbp");
  const SolveResult result = run_solver(*fbp, problem);
  CHECK(result.report.free_energy == Approx(-std::log(exact.partition)).epsilon(0).margin(1e-10));
  CHECK(max_abs_difference(result.marginals, exact.marginals) < 1e-10);
}

TEST_CASE("fbp: zero weights stay exactly zero", "[fbp]") {
  RandomStream rng(5, 2, 0);
  FractionalBpKernel kernel;
  for (int k = 0; k < 5; ++k) {
    const SingleScanProblem problem = random_problem(rng, 6, 6, Density::extreme, true);
    for (const double gamma : {0.0, 0.5, 1.0}) {
      const KernelRun run = run_kernel(kernel, problem, options_of(gamma, 1.0, 1.0));
      for (int i = 0; i < problem.targets(); ++i) {
        for (int j = 0; j < problem.measurements(); ++j) {
          if (problem.psi(i, j) == 0.0) CHECK(run.primal.q(i + 1, j + 1) == 0.0);
        }
      }
    }
  }
}

TEST_CASE("fbp: bad parameters are rejected naming the field", "[fbp]") {
  const auto message = [](const std::string& spec) {
    return input_error_message([&] { make_single_scan_solver(spec); });
  };
  CHECK_THAT(message("fbp:gamma=1.5"), Catch::Contains("gamma"));
  CHECK_THAT(message("fbp:gamma=-0.1"), Catch::Contains("gamma"));
  CHECK_THAT(message("fbp:alpha=0.5"), Catch::Contains("alpha"));
  CHECK_THAT(message("fbp:gamma=0.9,alpha=0.8"), Catch::Contains("alpha must be >= gamma"));
  CHECK_THAT(message("fbp:beta=0.4"), Catch::Contains("beta"));
  CHECK_THAT(message("fbp:gamma=0.9,beta=0.7"), Catch::Contains("beta must be >= gamma"));
  CHECK_THAT(message("fbp:tolerance=0"), Catch::Contains("tolerance"));
  CHECK_THAT(message("fbp:max_iterations=0"), Catch::Contains("max_iterations"));

  FractionalBpKernel kernel;
  RowMatrix w = RowMatrix::Constant(2, 3, 1.0);
  const Vector none;
  CHECK_THAT(input_error_message([&] { kernel.solve(w, none, none, options_of(0.5, 0.4, 1.0)); }),
             Catch::Contains("alpha"));
  w(1, 2) = -1.0;
  CHECK_THAT(input_error_message([&] { kernel.solve(w, none, none, FractionalBpOptions{}); }),
             Catch::Contains("w(2, 3)"));
  w(1, 2) = 1.0;
  CHECK_THAT(input_error_message([&] { kernel.solve(w, Vector::Ones(3), none, FractionalBpOptions{}); }),
             Catch::Contains("miss_weight"));
  CHECK_THAT(input_error_message([&] { kernel.solve(w, none, Vector::Zero(3), FractionalBpOptions{}); }),
             Catch::Contains("clutter_weight[1]"));
}

TEST_CASE("fbp: the kernel reads strided weight views", "[fbp]") {
  // Block (t', 1) of Algorithm 2 holds w^{i,j} for j = 0..m in one n×(m+1) matrix: the kernel
  // takes its columns 1..m and column 0 as views, with the same result as from copies.
  RandomStream rng(11, 3, 0);
  const SingleScanProblem problem = random_problem(rng, 4, 5, Density::sparse, true);
  RowMatrix all(4, 6);
  all.col(0) = problem.miss_weight;
  all.rightCols(5) = problem.psi;
  FractionalBpKernel kernel;
  const FractionalBpOptions options = options_of(0.5, 1.0, 0.8);
  kernel.solve(all.rightCols(5), all.col(0), problem.clutter_weight, options);
  const RowMatrix from_views = kernel.target_marginals();
  kernel.solve(problem.psi, problem.miss_weight, problem.clutter_weight, options);
  CHECK(max_abs_difference(from_views, RowMatrix(kernel.target_marginals())) == 0.0);
}

TEST_CASE("fbp: huge odds on a tree match brute force", "[fbp]") {
  // A pair 1e20 or 1e200 times likelier than its alternatives: "column sum minus own term" would
  // cancel to 0; the kernel must still give BP's (here exact) marginals, small ones included.
  for (const double odds : {1e20, 1e200}) {
    RowMatrix psi(3, 4);
    psi << 0.7, 2.0 * 1e10, 0.0, 0.0,  //
        0.0, 1.5, 0.3, 0.0,             //
        0.0, 0.0, 0.0, 4.0 * odds;
    SingleScanProblem problem;
    problem.psi = psi;
    problem.miss_weight = Vector(3);
    problem.miss_weight << 0.5, 2.0, 1.2;
    problem.clutter_weight = Vector(4);
    problem.clutter_weight << 1.0, 0.3, 3.0, 0.8;
    INFO("odds " << odds);
    const BruteForceResult exact = brute_force_marginals(problem);
    auto fbp = make_single_scan_solver("fbp");
    const SolveResult result = run_solver(*fbp, problem);
    REQUIRE(result.report.converged);
    const RowMatrix q = result.marginals;
    REQUIRE(q.allFinite());
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      for (Eigen::Index j = 0; j < q.cols(); ++j) {
        INFO("entry " << i << " " << j << ": " << q(i, j) << " vs " << exact.marginals(i, j));
        CHECK(std::fabs(q(i, j) - exact.marginals(i, j)) <= 1e-8 * exact.marginals(i, j));
      }
    }
  }
}

TEST_CASE("fbp: a dominant pair leaves the rest of the problem to the reduced problem", "[fbp]") {
  // With q_ij → 1 for one pair, (138) splits: row i and column j carry vanishing mass and
  // the other entries solve (138) on the problem without target i and measurement j. (At γ = 0
  // the split is only O(odds^{-1/2}) and Algorithm 1, then Sinkhorn scaling, needs ~1e5
  // iterations at odds 1e10: that case is left out.)
  RandomStream rng(77, 1, 0);
  const SingleScanProblem base = random_problem(rng, 4, 5, Density::dense, true);
  const int top_i = 1, top_j = 2;
  SingleScanProblem reduced;
  reduced.psi = RowMatrix(3, 4);
  reduced.miss_weight = Vector(3);
  reduced.clutter_weight = Vector(4);
  for (int i = 0, ri = 0; i < 4; ++i) {
    if (i == top_i) continue;
    reduced.miss_weight[ri] = base.miss_weight[i];
    for (int j = 0, rj = 0; j < 5; ++j) {
      if (j == top_j) continue;
      reduced.psi(ri, rj++) = base.psi(i, j);
    }
    ++ri;
  }
  for (int j = 0, rj = 0; j < 5; ++j) {
    if (j != top_j) reduced.clutter_weight[rj++] = base.clutter_weight[j];
  }
  FractionalBpKernel kernel;
  // β > 1 spreads q_0j (the mass left in column j decays like odds^{-1/β}): at 1e20 only β = 1.
  const std::pair<double, double> cases[] = {{1e20, 1.0}, {1e200, 1.0}, {1e200, 2.5}};
  for (const auto& [odds, beta] : cases) {
    for (const double gamma : {0.5, 0.95, 1.0}) {
      INFO("odds " << odds << " gamma " << gamma << " beta " << beta);
      SingleScanProblem problem = base;
      problem.psi(top_i, top_j) *= odds;
      const FractionalBpOptions options = options_of(gamma, 1.0, beta);
      const KernelRun run = run_kernel(kernel, problem, options);
      const KernelRun small = run_kernel(kernel, reduced, options);
      REQUIRE(run.outcome.converged);
      REQUIRE(run.primal.q.allFinite());
      CHECK(run.primal.q(top_i + 1, top_j + 1) > 1.0 - 1e-9);
      double largest_other = 0.0;  // the rest of row i and column j: positive and tiny
      for (int j = 0; j <= 5; ++j) {
        if (j != top_j + 1) largest_other = std::max(largest_other, run.primal.q(top_i + 1, j));
        CHECK((j == top_j + 1 || run.primal.q(top_i + 1, j) > 0.0));
      }
      for (int i = 0; i <= 4; ++i) {
        if (i != top_i + 1) largest_other = std::max(largest_other, run.primal.q(i, top_j + 1));
      }
      CHECK(largest_other < 1e-9);
      double difference = 0.0;
      for (int i = 0, ri = 0; i <= 4; ++i) {
        if (i == top_i + 1) continue;
        for (int j = 0, rj = 0; j <= 5; ++j) {
          if (j == top_j + 1) continue;
          if (i > 0 || j > 0) difference = std::max(difference, std::fabs(run.primal.q(i, j) - small.primal.q(ri, rj)));
          ++rj;
        }
        ++ri;
      }
      CHECK(difference < 1e-8);
    }
  }
}

TEST_CASE("fbp: weights whose row or column sum reaches 2^1020 are refused, not answered wrongly", "[fbp]") {
  // Two targets sharing a measurement of weight 1e308 (tests/fuzz/fuzz_weights): the sums overflow and
  // the messages gave p = ½, ½ for one target and 1, 0 for the other. One order lower: ½, ½ both.
  auto fbp = make_single_scan_solver("fbp");
  SingleScanProblem problem;
  problem.psi = RowMatrix::Constant(2, 1, 1e308);
  CHECK(run_solver(*fbp, problem).report.skipped == "numerical");
  problem.psi = RowMatrix::Constant(2, 1, 1e300);
  const SolveResult solved = run_solver(*fbp, problem);
  REQUIRE(solved.report.skipped.empty());
  for (int i = 0; i < 2; ++i) CHECK(solved.marginals(i, 1) == Approx(0.5).epsilon(1e-9));
}

}  // namespace DABENCH_TEST_FILE
