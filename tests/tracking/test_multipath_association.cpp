// Tests of Module 3 of JDT-VB (algorithms/multipath_association): loopy BP for the multipath
// association marginals E[a^{i,j,τ}] of one scan.
//  - the reading of constraint group (3): enumerating every binary a^{i,j,τ}, a^{0,j} under
//    (3a)-(3c) gives the same marginals as single-scan brute force on the pseudo-target
//    reduction (one pseudo-target per (target, path));
//  - BP without page factors is the BP paper's iteration on that reduction: it equals `bp` run to
//    δ = 1e-12;
//  - on trees (one measurement, or one pseudo-target) BP is exact, also with χ spread over
//    thousands of nats; gated-out pairs (χ = −∞) get exactly 0;
//  - at convergence every row and column of beliefs sums to 1 (with page factors too);
//  - bad evidence and options are rejected by name.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "algorithms/single_scan/bp.hpp"
#include "algorithms/tracking/multipath_association.hpp"
#include "harness/core/special_values.hpp"
#include "tests/support/brute_force.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

MultipathEvidence random_evidence(RandomStream& rng, int targets, int paths, int measurements, double gated_out) {
  MultipathEvidence evidence;
  evidence.targets = targets;
  evidence.paths = paths;
  const int rows = targets * paths;
  evidence.detection = RowMatrix(rows, measurements);
  for (int p = 0; p < rows; ++p) {
    for (int j = 0; j < measurements; ++j) {
      evidence.detection(p, j) = rng.bernoulli(gated_out) ? kMinusInfinity : rng.uniform(-3.0, 3.0);
    }
  }
  evidence.miss = Vector(rows);
  for (int p = 0; p < rows; ++p) evidence.miss[p] = rng.uniform(-2.0, 2.0);
  evidence.clutter = Vector(measurements);
  for (int j = 0; j < measurements; ++j) evidence.clutter[j] = rng.uniform(-2.0, 2.0);
  return evidence;
}

// Exact E[a] by visiting every binary a^{p,j} (p = i·paths + τ) and keeping the configurations
// that satisfy (3a) Σ_p a^{p,j} ≤ 1 per measurement, (3b) Σ_j a^{p,j} ≤ 1 per (target, path) and
// (3c) Σ_τ a^{i,j,τ} ≤ 1; the slacks a^{0,j}, a^{p,0} are then determined. Weight of a
// configuration: exp of the sum of χ over the active variables (eq 43).
MultipathAssociation enumerate_exact(const MultipathEvidence& evidence) {
  const int rows = evidence.pseudo_targets(), columns = evidence.measurements();
  const int variables = rows * columns;
  REQUIRE(variables <= 20);
  MultipathAssociation exact;
  exact.detection = RowMatrix::Zero(rows, columns);
  exact.miss = Vector::Zero(rows);
  exact.clutter = Vector::Zero(columns);
  double partition = 0.0;
  std::vector<int> row_count(rows), column_count(columns);
  for (std::uint32_t bits = 0; bits < (1u << variables); ++bits) {
    std::fill(row_count.begin(), row_count.end(), 0);
    std::fill(column_count.begin(), column_count.end(), 0);
    bool feasible = true;
    double log_weight = 0.0;
    for (int v = 0; v < variables; ++v) {
      if (!(bits >> v & 1u)) continue;
      const int p = v / columns, j = v % columns;
      log_weight += evidence.detection(p, j);
      if (++row_count[p] > 1 || ++column_count[j] > 1) feasible = false;
    }
    for (int first = 0; feasible && first < rows; first += evidence.paths) {
      for (int j = 0; j < columns; ++j) {
        int paths_used = 0;
        for (int tau = 0; tau < evidence.paths; ++tau) paths_used += bits >> ((first + tau) * columns + j) & 1u;
        if (paths_used > 1) feasible = false;  // (3c)
      }
    }
    if (!feasible) continue;
    for (int p = 0; p < rows; ++p) log_weight += row_count[p] == 0 ? evidence.miss[p] : 0.0;
    for (int j = 0; j < columns; ++j) log_weight += column_count[j] == 0 ? evidence.clutter[j] : 0.0;
    const double weight = std::exp(log_weight);
    partition += weight;
    for (int v = 0; v < variables; ++v) {
      if (bits >> v & 1u) exact.detection(v / columns, v % columns) += weight;
    }
    for (int p = 0; p < rows; ++p) exact.miss[p] += row_count[p] == 0 ? weight : 0.0;
    for (int j = 0; j < columns; ++j) exact.clutter[j] += column_count[j] == 0 ? weight : 0.0;
  }
  exact.detection /= partition;
  exact.miss /= partition;
  exact.clutter /= partition;
  return exact;
}

// The pseudo-target reduction: ψ = e^χ, w_p0 = e^{χ^{p,0}}, w_0j = e^{χ^{0,j}}.
SingleScanProblem pseudo_target_problem(const MultipathEvidence& evidence) {
  SingleScanProblem problem;
  problem.psi = evidence.detection.array().exp();
  problem.miss_weight = evidence.miss.array().exp();
  problem.clutter_weight = evidence.clutter.array().exp();
  return problem;
}

// E[a] as an n×(m+1) table with the miss in column 0, as single-scan solvers report it.
RowMatrix as_table(const MultipathAssociation& association) {
  RowMatrix table(association.detection.rows(), association.detection.cols() + 1);
  table.col(0) = association.miss;
  table.rightCols(association.detection.cols()) = association.detection;
  return table;
}

MultipathAssociation solve(const MultipathEvidence& evidence, MultipathAssociationOptions options = {}) {
  MultipathAssociationBp bp;
  MultipathAssociation result;
  bp.solve(evidence, options, result);
  return result;
}

double largest_sum_violation(const MultipathAssociation& a) {
  double worst = 0.0;
  for (int p = 0; p < a.detection.rows(); ++p) worst = std::max(worst, std::abs(a.detection.row(p).sum() + a.miss[p] - 1.0));
  for (int j = 0; j < a.detection.cols(); ++j) worst = std::max(worst, std::abs(a.detection.col(j).sum() + a.clutter[j] - 1.0));
  return worst;
}

}  // namespace

TEST_CASE("multipath: constraints (3a)-(3c) give the pseudo-target single-scan posterior", "[multipath]") {
  RandomStream rng(31, 0, 0);
  for (int trial = 0; trial < 12; ++trial) {
    const int targets = 1 + trial % 2, paths = 1 + trial % 3, measurements = 1 + trial % 4;
    if (targets * paths * measurements > 16) continue;
    const MultipathEvidence evidence = random_evidence(rng, targets, paths, measurements, 0.25);
    const MultipathAssociation exact = enumerate_exact(evidence);
    const BruteForceResult reduced = brute_force_marginals(pseudo_target_problem(evidence));
    INFO("trial " << trial << ": " << targets << " targets, " << paths << " paths, " << measurements << " measurements");
    CHECK(max_abs_difference(as_table(exact), reduced.marginals) < 1e-12);
  }
}

TEST_CASE("multipath: without page factors BP equals bp on the pseudo-target reduction", "[multipath]") {
  RandomStream rng(32, 0, 0);
  BpOptions reference_options;
  reference_options.delta = 1e-12;
  for (int trial = 0; trial < 20; ++trial) {
    const MultipathEvidence evidence = random_evidence(rng, 3, 3, 6, trial % 2 == 0 ? 0.0 : 0.5);
    const MultipathAssociation ours = solve(evidence, {.tolerance = 1e-13});
    REQUIRE(ours.converged);
    BeliefPropagation reference(reference_options);
    const SolveResult expected = run_solver(reference, pseudo_target_problem(evidence));
    INFO("trial " << trial << ", " << ours.iterations << " iterations");
    CHECK(max_abs_difference(as_table(ours), expected.marginals) < 1e-9);
    // bp reports target-side marginals only; a measurement's clutter belief is 1 − its column.
    for (int j = 0; j < evidence.measurements(); ++j) {
      CHECK(ours.clutter[j] == Approx(1.0 - expected.marginals.col(j + 1).sum()).margin(1e-9));
    }
  }
}

TEST_CASE("multipath: BP is exact on trees (one measurement or one pseudo-target)", "[multipath]") {
  RandomStream rng(33, 0, 0);
  for (int trial = 0; trial < 10; ++trial) {
    const bool one_measurement = trial % 2 == 0;
    const MultipathEvidence evidence = one_measurement ? random_evidence(rng, 3, 2, 1, 0.2)
                                                       : random_evidence(rng, 1, 1, 7, 0.2);
    const MultipathAssociation ours = solve(evidence, {.tolerance = 1e-14});
    REQUIRE(ours.converged);
    const MultipathAssociation exact = enumerate_exact(evidence);
    INFO("trial " << trial);
    CHECK(max_abs_difference(as_table(ours), as_table(exact)) < 1e-12);
    CHECK(max_abs_difference(ours.clutter.transpose(), exact.clutter.transpose()) < 1e-12);
  }
}

TEST_CASE("multipath: evidence spread over thousands of nats stays finite and exact on a tree", "[multipath]") {
  MultipathEvidence evidence;
  evidence.targets = 2;
  evidence.paths = 2;
  evidence.detection = RowMatrix(4, 1);
  evidence.detection << 2000.0, 1990.0, -1500.0, kMinusInfinity;
  evidence.miss = Vector::Constant(4, 0.0);
  evidence.clutter = Vector::Constant(1, 5.0);
  const MultipathAssociation ours = solve(evidence);
  REQUIRE(ours.converged);
  CHECK(ours.detection.allFinite());
  // Exact: the measurement is path 0 of target 0 unless it is path 1 (odds e^{-10}).
  const double second = 1.0 / (1.0 + std::exp(10.0));
  CHECK(ours.detection(0, 0) == Approx(1.0 - second).epsilon(1e-12));
  CHECK(ours.detection(1, 0) == Approx(second).epsilon(1e-9));
  CHECK(ours.detection(3, 0) == 0.0);  // gated out stays exactly 0
  CHECK(ours.detection(2, 0) < 1e-300);
  CHECK(ours.miss[0] == Approx(second).epsilon(1e-9));
  CHECK(ours.miss[2] == 1.0);
  CHECK(ours.clutter[0] < 1e-300);
}

TEST_CASE("multipath: converged beliefs of every row and column sum to one", "[multipath]") {
  RandomStream rng(34, 0, 0);
  for (const bool page : {false, true}) {
    for (int trial = 0; trial < 10; ++trial) {
      const MultipathEvidence evidence = random_evidence(rng, 4, 3, 8, 0.4);
      const MultipathAssociation ours = solve(evidence, {.tolerance = 1e-12, .page_factor = page});
      INFO("page factor " << page << ", trial " << trial);
      REQUIRE(ours.converged);
      CHECK(largest_sum_violation(ours) < 1e-9);
      CHECK((ours.detection.array() >= 0.0).all());
    }
  }
}

TEST_CASE("multipath: page factors change nothing with one path and little with several", "[multipath]") {
  RandomStream rng(35, 0, 0);
  for (int trial = 0; trial < 6; ++trial) {
    const MultipathEvidence single_path = random_evidence(rng, 4, 1, 5, 0.3);
    CHECK(max_abs_difference(as_table(solve(single_path, {.page_factor = true})), as_table(solve(single_path))) == 0.0);
  }
  // Several paths: both are approximations of the same exact posterior (the page factor is
  // implied by (3a)); neither may be far from it on these small, well-separated problems.
  for (int trial = 0; trial < 6; ++trial) {
    const MultipathEvidence evidence = random_evidence(rng, 2, 2, 4, 0.3);
    const MultipathAssociation exact = enumerate_exact(evidence);
    for (const bool page : {false, true}) {
      INFO("trial " << trial << ", page factor " << page);
      CHECK(max_abs_difference(as_table(solve(evidence, {.page_factor = page})), as_table(exact)) < 0.1);
    }
  }
}

TEST_CASE("multipath: empty scans", "[multipath]") {
  MultipathEvidence no_measurements;
  no_measurements.targets = 2;
  no_measurements.paths = 3;
  no_measurements.detection = RowMatrix(6, 0);
  no_measurements.miss = Vector::Constant(6, -1.0);
  no_measurements.clutter = Vector(0);
  const MultipathAssociation a = solve(no_measurements);
  CHECK(a.converged);
  CHECK((a.miss.array() == 1.0).all());

  MultipathEvidence no_targets;
  no_targets.paths = 2;
  no_targets.detection = RowMatrix(0, 3);
  no_targets.miss = Vector(0);
  no_targets.clutter = Vector::Constant(3, 0.5);
  const MultipathAssociation b = solve(no_targets);
  CHECK((b.clutter.array() == 1.0).all());
}

TEST_CASE("multipath: bad evidence and options are rejected by name", "[multipath]") {
  RandomStream rng(36, 0, 0);
  const MultipathEvidence good = random_evidence(rng, 2, 2, 3, 0.0);
  MultipathAssociationBp bp;
  MultipathAssociation result;
  auto message = [&](const MultipathEvidence& evidence, MultipathAssociationOptions options = {}) {
    return input_error_message([&] { bp.solve(evidence, options, result); });
  };
  MultipathEvidence wrong_rows = good;
  wrong_rows.paths = 3;
  CHECK_THAT(message(wrong_rows), Catch::Contains("expected 6 (targets x paths)"));
  MultipathEvidence wrong_clutter = good;
  wrong_clutter.clutter = Vector::Zero(2);
  CHECK_THAT(message(wrong_clutter), Catch::Contains("2 clutter entries for 3 measurements"));
  MultipathEvidence nan_detection = good;
  nan_detection.detection(1, 2) = std::nan("");
  CHECK_THAT(message(nan_detection), Catch::Contains("NaN or +inf"));
  MultipathEvidence infinite_miss = good;
  infinite_miss.miss[0] = kMinusInfinity;
  CHECK_THAT(message(infinite_miss), Catch::Contains("miss or clutter evidence"));
  MultipathEvidence no_paths = good;
  no_paths.paths = 0;
  CHECK_THAT(message(no_paths), Catch::Contains("0 paths"));
  CHECK_THAT(message(good, {.tolerance = 0.0}), Catch::Contains("tolerance must be > 0"));
  CHECK_THAT(message(good, {.max_iterations = 0}), Catch::Contains("max_iterations must be >= 1"));
}

}  // namespace DABENCH_TEST_FILE
