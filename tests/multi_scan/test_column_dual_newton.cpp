// Tests of the reduced column-dual solver (ColumnDualSolver, column_dual_newton.hpp) for the
// multiple-scan convex free energy (63) of multiscan-convex-variational:
//  - agreement with Algorithm 2 run to its limit (λ tolerance 1e-12, no belief-rate stopping,
//    a large sweep cap) on random problems and small bearings problems, for cv, cvs, cvh, cvsh:
//    beliefs within 1e-9;
//  - the KKT conditions of (63) evaluated independently at the solver's pair beliefs
//    (tests/support/free_energy_kkt.hpp), the column constraints (61) and strong duality (the
//    dual value equals (63) evaluated at the beliefs);
//  - Theorem 3: after a reweight with the modification (91) the next solve takes no step;
//  - L-BFGS (Hessian-free) reaches the same beliefs as Newton;
//  - structural zeros, a track that can only miss, an infeasible track, an empty scan.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "algorithms/multi_scan/column_dual_newton.hpp"
#include "algorithms/multi_scan/convex_variational.hpp"
#include "harness/core/params.hpp"
#include "scenarios/multi_scan/bearings.hpp"
#include "tests/support/free_energy_kkt.hpp"
#include "tests/support/multi_scan.hpp"
#include "tests/support/sanitized.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

ColumnDualSettings newton() {
  ColumnDualSettings settings;
  settings.method = DualMethod::kNewton;
  return settings;
}

// Solves (63) on all scans at once with the given coefficients (no modification by (91)).
struct DualSolve {
  ColumnDualSolver solver;
  SolveReport report;
  MultiScanBeliefs beliefs;
};

void solve_batch(DualSolve& run, const MultiScanProblem& problem, const std::vector<double>& gamma,
                 const std::vector<double>& beta, const ColumnDualSettings& settings) {
  run.solver.start(problem);
  for (const ScanFactors& scan : problem.scans) run.solver.append_scan(scan);
  run.solver.reweight(gamma, beta);
  run.report.reset();
  run.solver.solve(settings, run.report);
  if (run.report.skipped.empty()) run.solver.write_beliefs(run.beliefs);
}

FreeEnergyPoint point_of(const ColumnDualSolver& solver, const MultiScanProblem& problem, const MultiScanBeliefs& beliefs) {
  FreeEnergyPoint point{beliefs.track, {}, {}};
  for (int t = 0; t < problem.scan_count(); ++t) {
    point.pair.emplace_back();
    for (int i = 0; i < problem.tracks(); ++i) point.pair[t].push_back(solver.pair_belief(i, t));
    point.clutter.push_back(solver.clutter(t));
  }
  return point;
}

// (63) evaluated at a point, term by term.
double free_energy(const MultiScanProblem& problem, const FreeEnergyPoint& point, const std::vector<double>& gamma,
                   const std::vector<double>& beta) {
  const int scans = problem.scan_count();
  double value = 0.0;
  for (int i = 0; i < problem.tracks(); ++i) {
    const Vector& q = point.track[i];
    for (Eigen::Index h = 0; h < q.size(); ++h) {
      if (q[h] > 0.0) value += (1.0 - scans) * q[h] * std::log(q[h]) - q[h] * std::log(problem.prior[i][h]);
    }
    for (int t = 0; t < scans; ++t) {
      const RowMatrix& pair = point.pair[t][i];
      for (Eigen::Index h = 0; h < pair.rows(); ++h) {
        for (Eigen::Index a = 0; a < pair.cols(); ++a) {
          if (pair(h, a) > 0.0) value += pair(h, a) * (std::log(pair(h, a)) - std::log(problem.scans[t].factor[i](h, a)));
        }
      }
      const Eigen::RowVectorXd marginal = pair.colwise().sum();
      for (Eigen::Index j = 1; j < pair.cols(); ++j) value -= gamma[t] * (1.0 - marginal[j]) * std::log1p(-marginal[j]);
    }
  }
  for (int t = 0; t < scans; ++t) {
    for (double c : point.clutter[t]) value += beta[t] * c * std::log(c);
  }
  return value;
}

PdcaSettings limit(KappaWeights weights) {
  PdcaSettings settings;
  settings.weights = weights;
  settings.tolerance = 1e-12;
  settings.belief_tolerance = 0.0;
  settings.max_sweeps = 200000;
  settings.kernel_tolerance = 1e-13;
  settings.kernel_max_iterations = 100000;
  return settings;
}

// β_t = β̃ K1_t as the registered methods set it.
std::vector<double> betas(KappaWeights weights, const std::vector<double>& gamma) {
  std::vector<double> beta(gamma.size());
  for (std::size_t t = 0; t < gamma.size(); ++t) {
    beta[t] = ConvexVariationalPdca::block_scale(weights, gamma, static_cast<int>(t));
  }
  return beta;
}

MultiScanProblem bearings_problem(int targets, int particles, int scans_per_sensor, std::uint32_t trial) {
  const BearingsScenario scenario(make_options<BearingsOptions>(
      {{"mean_targets", std::to_string(targets)}, {"poisson_targets", "0"}, {"particles", std::to_string(particles)},
       {"scans_per_sensor", std::to_string(scans_per_sensor)}},
      "bearings"));
  RandomStream rng(2017, 0, trial);
  MultiScanSample sample;
  scenario.generate(rng, sample);
  return sample.problem;
}

// Newton on (63) with the given γ (β from Lemma 4): KKT conditions, column feasibility and
// strong duality on three random problems of the shape.
void check_optimality(const RandomMultiScanShape& shape, const std::vector<double>& gamma, std::uint64_t seed_base) {
  const std::vector<double> beta = betas(KappaWeights::kLemma4, gamma);
  for (std::uint64_t seed = seed_base; seed < seed_base + 3; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem(shape, seed);
    DualSolve run;
    solve_batch(run, problem, gamma, beta, newton());
    INFO("seed " << seed << " iterations " << run.report.iterations);
    REQUIRE(run.report.skipped.empty());
    REQUIRE(run.report.converged);
    CHECK(run.report.residual <= 1e-12);
    const FreeEnergyPoint point = point_of(run.solver, problem, run.beliefs);
    CHECK(projected_gradient(problem, point, gamma, beta) < 1e-10);
    CHECK(constraint_violation(point) < 1e-12);
    CHECK(run.solver.dual_value() == Approx(free_energy(problem, point, gamma, beta)).epsilon(1e-12).margin(1e-10));
  }
}

// Newton against Algorithm 2 at its limit on two random problems of the shape.
void check_against_pdca(const RandomMultiScanShape& shape, const std::vector<double>& gamma, KappaWeights weights,
                        std::uint64_t seed_base) {
  const std::vector<double> beta = betas(weights, gamma);
  for (std::uint64_t seed = seed_base; seed < seed_base + 2; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem(shape, seed);
    DualSolve run;
    solve_batch(run, problem, gamma, beta, newton());
    ConvexVariationalPdca pdca;
    pdca.start(problem);
    for (const ScanFactors& scan : problem.scans) pdca.append_scan(scan);
    pdca.reweight(gamma, beta);
    SolveReport report;
    pdca.solve(limit(weights), report);
    MultiScanBeliefs reference;
    pdca.write_beliefs(reference);
    INFO("seed " << seed << " newton " << run.report.iterations << " sweeps " << report.iterations);
    REQUIRE(report.converged);
    REQUIRE(run.report.converged);
    CHECK(belief_difference(run.beliefs, reference) < 1e-9);
  }
}

}  // namespace

TEST_CASE("column dual: the solution is a KKT point of (63) and strong duality holds") {
  check_optimality({3, 3, {2, 3, 2}, 0.0}, {0.25, 0.25, 0.25}, 1);      // cv
  check_optimality({2, 4, {3, 2}, 0.0}, {0.7, 0.1}, 101);
  check_optimality({4, 3, {3, 3, 1, 2}, 0.0}, {0.0, 0.0, 0.0, 0.95}, 201);  // a cvs step
  check_optimality({3, 2, {2, 2, 2}, 0.0}, {0.0, 0.0, 0.0}, 301);        // no γ-scan
}

TEST_CASE("column dual: agrees with Algorithm 2 at its limit on random problems") {
  check_against_pdca({3, 4, {2, 3, 2}, 0.0}, {0.25, 0.25, 0.25}, KappaWeights::kLemma4, 1);     // cv
  check_against_pdca({3, 3, {3, 2}, 0.3}, {1.0 / 3, 1.0 / 3}, KappaWeights::kHeuristic, 201);    // cvh, with zeros
  check_against_pdca({2, 5, {2, 2, 3}, 0.0}, {0.1, 0.5, 0.3}, KappaWeights::kLemma4, 401);
}

TEST_CASE("column dual: the registered sequential and batch methods agree with their Algorithm-2 form") {
  // cvs/cvsh run one solve per scan with the Theorem-3 modification between steps, so this also
  // checks that both engines modify the factors identically.
  const std::string pdca_limit = "solver=pdca,tolerance=1e-12,belief_tolerance=0,max_sweeps=200000";
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem({3, 3, {2, 3, 2}, 0.1}, 300 + seed);
    for (const std::string method : {"cv", "cvs", "cvs:gamma=0.55", "cvh", "cvsh"}) {
      const char separator = method.find(':') == std::string::npos ? ':' : ',';
      const std::string pdca_spec = method + separator + pdca_limit;
      const MultiScanRun reference = run_multi_scan(pdca_spec, problem);
      const MultiScanRun run = run_multi_scan(method, problem);
      INFO(method << " seed " << seed << " newton " << run.report.iterations << " sweeps " << reference.report.iterations);
      REQUIRE(reference.report.converged);
      REQUIRE(run.report.converged);
      CHECK(belief_difference(run.beliefs, reference.beliefs) < 1e-9);
    }
  }
}

TEST_CASE("column dual: agrees with Algorithm 2 on small bearings problems", "[bearings]") {
  // 3 targets, 20 particles per track (+ the truth probe), 4 scans: the paper's factors, with
  // their wide dynamic range (likelihood ratios near e^6 against misses, near-certain associations).
  const std::string pdca_limit = ":solver=pdca,tolerance=1e-12,belief_tolerance=0,max_sweeps=200000";
  for (std::uint32_t trial = 0; trial < static_cast<std::uint32_t>(dabench::test::sanitized_size(2, 2)); ++trial) {
    const MultiScanProblem problem = bearings_problem(3, 20, 1, trial);
    for (const std::string method : {"cv", "cvs"}) {
      const MultiScanRun reference = run_multi_scan(method + pdca_limit, problem);
      const MultiScanRun run = run_multi_scan(method, problem);
      INFO(method << " trial " << trial << " newton " << run.report.iterations << " sweeps " << reference.report.iterations);
      REQUIRE(reference.report.converged);
      REQUIRE(run.report.converged);
      CHECK(belief_difference(run.beliefs, reference.beliefs) < 1e-9);
    }
  }
}

TEST_CASE("column dual: after a Theorem-3 reweight the next solve takes no step") {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem({3, 3, {2, 3, 3}, 0.0}, 400 + seed);
    ColumnDualSolver solver;
    solver.start(problem);
    for (const ScanFactors& scan : problem.scans) solver.append_scan(scan);
    solver.reweight({0.2, 0.3, 0.45}, {0.5, 0.6, 0.7});
    SolveReport first;
    solver.solve(newton(), first);
    REQUIRE(first.converged);
    REQUIRE(first.iterations > 0);
    MultiScanBeliefs before, after;
    solver.write_beliefs(before);
    solver.reweight({0.0, 0.0, 0.95}, {0.02, 0.3, 0.97});  // as a CVS step does: γ moves to the newest scan
    SolveReport second;
    solver.solve(newton(), second);
    solver.write_beliefs(after);
    INFO("seed " << seed);
    CHECK(second.iterations == 0);
    CHECK(second.converged);
    CHECK(belief_difference(before, after) < 1e-13);
  }
}

TEST_CASE("column dual: L-BFGS reaches the Newton solution") {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const MultiScanProblem problem = random_multi_scan_problem({4, 3, {3, 2, 3}, 0.1}, 500 + seed);
    const std::vector<double> gamma = {0.0, 0.0, 0.9};
    const std::vector<double> beta = betas(KappaWeights::kLemma4, gamma);
    DualSolve exact, limited;
    solve_batch(exact, problem, gamma, beta, newton());
    ColumnDualSettings lbfgs;
    lbfgs.method = DualMethod::kLbfgs;
    lbfgs.max_iterations = 5000;
    solve_batch(limited, problem, gamma, beta, lbfgs);
    INFO("seed " << seed << " newton " << exact.report.iterations << " lbfgs " << limited.report.iterations);
    REQUIRE(exact.report.converged);
    REQUIRE(limited.report.converged);
    CHECK(belief_difference(exact.beliefs, limited.beliefs) < 1e-9);
  }
}

TEST_CASE("column dual: structural cases") {
  SECTION("a track that can only miss, and a scan without measurements") {
    MultiScanProblem problem = random_multi_scan_problem({3, 3, {2, 0, 3}, 0.0}, 9);
    for (ScanFactors& scan : problem.scans) scan.factor[1].rightCols(scan.measurements).setZero();
    const MultiScanRun run = run_multi_scan("cvs", problem);
    REQUIRE(run.report.skipped.empty());
    REQUIRE(run.report.converged);
    for (int t = 0; t < 3; ++t) CHECK(run.beliefs.association[t](1, 0) == Approx(1.0).margin(1e-15));
    const MultiScanRun reference = run_multi_scan("cvs:solver=pdca,tolerance=1e-12,belief_tolerance=0,max_sweeps=200000", problem);
    CHECK(belief_difference(run.beliefs, reference.beliefs) < 1e-9);
  }
  SECTION("a track certain to take one measurement: no interior point, so Algorithm 2 solves it") {
    MultiScanProblem problem = random_multi_scan_problem({2, 3, {3, 2}, 0.0}, 10);
    RowMatrix& factor = problem.scans[0].factor[0];
    factor.setZero();
    factor.col(2).setConstant(0.7);
    CHECK_FALSE(ColumnDualSolver::applicable(problem));
    const MultiScanRun run = run_multi_scan("cvs", problem);
    INFO(run.report.skipped);
    REQUIRE(run.report.skipped.empty());
    REQUIRE(run.report.converged);
    CHECK(run.beliefs.association[0](0, 2) == Approx(1.0).margin(1e-15));
    CHECK(run.beliefs.association[0](1, 2) == Approx(0.0).margin(1e-12));
  }
  SECTION("a hypothesis no scan can follow is removed, and a track with none left is infeasible") {
    MultiScanProblem problem = random_multi_scan_problem({2, 3, {2, 2}, 0.0}, 11);
    problem.scans[1].factor[0].row(2).setZero();
    const MultiScanRun run = run_multi_scan("cv", problem);
    REQUIRE(run.report.skipped.empty());
    CHECK(run.beliefs.track[0][2] == 0.0);
    for (ScanFactors& scan : problem.scans) scan.factor[1].setZero();
    CHECK(run_multi_scan("cv", problem).report.skipped == "zero_partition");
  }
}

TEST_CASE("column dual: solver options") {
  CHECK_THROWS_AS(make_multi_scan_solver("cv:solver=simplex"), InputError);
  CHECK_THROWS_AS(make_multi_scan_solver("cvs:residual_tolerance=0"), InputError);
  CHECK_THROWS_AS(make_multi_scan_solver("cvsh:gamma=1,solver=newton"), InputError);
  CHECK_NOTHROW(make_multi_scan_solver("cvsh:gamma=1"));  // auto: Algorithm 2
  CHECK_THROWS_AS(make_multi_scan_solver("msbp:solver=newton"), InputError);
  CHECK_NOTHROW(make_multi_scan_solver("cv:solver=lbfgs,max_iterations=50"));
}

// A factor that overflows to infinity or is NaN makes the dual non-finite: the solve ends as
// skipped:numerical (never beliefs from a failed evaluation), for Newton and L-BFGS.
TEST_CASE("column dual: a non-finite factor ends the solve as skipped:numerical") {
  const std::vector<double> gamma = {0.5, 0.5, 0.5};
  const std::vector<double> beta = betas(KappaWeights::kLemma4, gamma);
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    for (const DualMethod method : {DualMethod::kNewton, DualMethod::kLbfgs}) {
      MultiScanProblem problem = random_multi_scan_problem({3, 3, {2, 3, 2}, 0.1}, 41);
      problem.scans[1].factor[0](1, 1) = bad;
      DualSolve run;
      ColumnDualSettings settings;
      settings.method = method;
      solve_batch(run, problem, gamma, beta, settings);
      INFO("factor " << bad << (method == DualMethod::kNewton ? ", Newton" : ", L-BFGS"));
      CHECK(run.report.skipped == "numerical");
    }
  }
}

}  // namespace DABENCH_TEST_FILE
