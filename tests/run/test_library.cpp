// Tests of the library entry point (harness/run/library.hpp):
//  - make_single_scan_problem validates ψ and keeps the model constants;
//  - solving by SPEC and by typed options gives bit-identical marginals and diagnostics;
//  - the marginals are the right numbers: exact against brute-force enumeration, BP on a tree
//    (where it is exact, bp-marginal-association Sec. III) likewise, W* = max_i Σ_j ψ_i(j);
//  - a bad SPEC, bad typed options or a bad problem is an InputError with the same message
//    either way; a refused problem is a `skipped` report with no marginals;
//  - run_experiment writes the rows of an experiment file.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "algorithms/single_scan/bp.hpp"
#include "algorithms/single_scan/exact_enumeration.hpp"
#include "harness/run/library.hpp"
#include "tests/support/brute_force.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

// Three targets all gating three measurements: the gating graph has cycles, BP is approximate.
RowMatrix loopy_weights() {
  RowMatrix psi(3, 3);
  psi << 2.0, 0.5, 1.0,
         1.5, 3.0, 0.2,
         0.7, 1.1, 4.0;
  return psi;
}

// Measurement 1 is shared by both targets, the others are exclusive: the graph is a tree.
RowMatrix tree_weights() {
  RowMatrix psi(2, 3);
  psi << 2.0, 0.5, 0.0,
         1.5, 0.0, 3.0;
  return psi;
}

void check_identical(const SingleScanResult& a, const SingleScanResult& b) {
  REQUIRE(a.report.skipped.empty());
  REQUIRE(b.report.skipped.empty());
  REQUIRE(a.marginals.targets() == b.marginals.targets());
  REQUIRE(a.marginals.measurements() == b.marginals.measurements());
  for (int i = 0; i < a.marginals.targets(); ++i) {
    for (int j = 0; j <= a.marginals.measurements(); ++j) CHECK(a.marginals(i, j) == b.marginals(i, j));
  }
  CHECK(a.report.iterations == b.report.iterations);
  CHECK(a.report.converged == b.report.converged);
  CHECK((a.report.w_star == b.report.w_star || (std::isnan(a.report.w_star) && std::isnan(b.report.w_star))));
}

}  // namespace

TEST_CASE("library: a problem from a weight matrix is validated and keeps its context", "[library]") {
  const SingleScanProblem problem = make_single_scan_problem(tree_weights(), {.pd = 0.6, .lambda_fa = 0.01});
  CHECK(problem.targets() == 2);
  CHECK(problem.measurements() == 3);
  CHECK(problem.psi(1, 2) == 3.0);
  CHECK(problem.context.pd == 0.6);
  CHECK(problem.context.lambda_fa == 0.01);
  CHECK(problem.has_unit_side_weights());

  RowMatrix negative = tree_weights();
  negative(0, 1) = -0.5;
  CHECK(input_error_message([&] { make_single_scan_problem(negative); }) ==
        "problem: weight psi[1][2] = -0.5 (must be finite and >= 0)");
  RowMatrix not_a_number = tree_weights();
  not_a_number(1, 0) = std::numeric_limits<double>::quiet_NaN();
  CHECK(input_error_message([&] { make_single_scan_problem(not_a_number); }).find("psi[2][1]") != std::string::npos);
}

TEST_CASE("library: SPEC and typed options give bit-identical results", "[library]") {
  const SingleScanProblem problem = make_single_scan_problem(loopy_weights());
  const SingleScanResult by_spec = solve_single_scan("bp:delta=1e-9,check_every=10", problem);
  const SingleScanResult typed = solve_single_scan<BeliefPropagation>(problem, {.check_every = 10, .delta = 1e-9});
  check_identical(by_spec, typed);
  CHECK(by_spec.report.iterations % 10 == 0);  // checked every 10 iterations
  // Defaults: the bare name and a default-constructed Options.
  check_identical(solve_single_scan("bp", problem), solve_single_scan<BeliefPropagation>(problem));

  // Exact: both paths equal brute-force enumeration of every consistent event (eq 12).
  const SingleScanResult exact_spec = solve_single_scan("exact", problem);
  check_identical(exact_spec, solve_single_scan<ExactEnumeration>(problem, {}));
  CHECK(max_abs_difference(to_matrix(exact_spec.marginals), brute_force_marginals(problem).marginals) < 1e-12);
  // BP on this loopy graph is close to exact but not equal to it.
  const double bp_error = max_abs_difference(to_matrix(by_spec.marginals), to_matrix(exact_spec.marginals));
  CHECK(bp_error > 1e-6);
  CHECK(bp_error < 0.05);
}

TEST_CASE("library: diagnostics are filled and the marginals are right", "[library]") {
  const SingleScanProblem problem = make_single_scan_problem(tree_weights());
  const SingleScanResult result = solve_single_scan("bp:delta=1e-12", problem);
  REQUIRE(result.report.skipped.empty());
  CHECK(result.report.w_star == 4.5);  // W* = max(2 + 0.5, 1.5 + 3), Lemma 2
  CHECK(result.report.iterations >= 1);
  CHECK(result.report.converged);
  REQUIRE(result.marginals.targets() == 2);
  REQUIRE(result.marginals.measurements() == 3);
  // A tree: BP is exact.
  CHECK(max_abs_difference(to_matrix(result.marginals), brute_force_marginals(problem).marginals) < 1e-9);
  CHECK(result.marginals(0, 3) == 0.0);  // not gated stays exactly zero
  for (int i = 0; i < 2; ++i) CHECK(std::fabs(to_matrix(result.marginals).row(i).sum() - 1.0) < 1e-12);
}

TEST_CASE("library: bad SPECs, options and problems are InputErrors", "[library]") {
  const SingleScanProblem problem = make_single_scan_problem(loopy_weights());
  CHECK(input_error_message([&] { solve_single_scan("nosuch", problem); }).find("unknown algorithm 'nosuch'") !=
        std::string::npos);
  CHECK(input_error_message([&] { solve_single_scan("bp:tol=1e-9", problem); }).find("tol") != std::string::npos);
  CHECK(input_error_message([&] { solve_single_scan("bp:delta=abc", problem); }).find("delta") != std::string::npos);
  // An invalid value: the same message by SPEC and by typed options.
  const std::string by_spec = input_error_message([&] { solve_single_scan("bp:delta=-1", problem); });
  const std::string typed =
      input_error_message([&] { solve_single_scan<BeliefPropagation>(problem, {.delta = -1.0}); });
  CHECK(by_spec == "bp: delta must be > 0");
  CHECK(typed == by_spec);
  // A problem built by hand is validated before any algorithm sees it.
  SingleScanProblem bad = problem;
  bad.psi(2, 2) = std::numeric_limits<double>::infinity();
  CHECK(input_error_message([&] { solve_single_scan("bp", bad); }).find("psi[3][3] = inf") != std::string::npos);
  bad = problem;
  bad.miss_weight = Vector::Ones(2);
  CHECK(input_error_message([&] { solve_single_scan<BeliefPropagation>(bad); }) ==
        "problem: 2 missed-detection weights for 3 targets");
}

TEST_CASE("library: a refused problem is reported, with no marginals", "[library]") {
  // lmipda needs Pd on a problem with shared measurements.
  const SingleScanResult refused = solve_single_scan("lmipda", make_single_scan_problem(loopy_weights()));
  CHECK(refused.report.skipped == "needs_pd");
  CHECK(refused.marginals.targets() == 0);
  const SingleScanResult solved = solve_single_scan("lmipda", make_single_scan_problem(loopy_weights(), {.pd = 0.9}));
  CHECK(solved.report.skipped.empty());
  CHECK(solved.marginals.targets() == 3);
  // A work limit below the problem's event count.
  const SingleScanResult limited = solve_single_scan("exact:max_events=2", make_single_scan_problem(loopy_weights()));
  CHECK(limited.report.skipped == "work_limit");
  CHECK(limited.marginals.targets() == 0);
}

TEST_CASE("library: run_experiment runs an experiment file", "[library]") {
  cli::TempDir dir;
  dir.write("tiny.ini",
            "scenario = grid\n"
            "trials = 3\n"
            "seed = 5\n"
            "reference = exact\n"
            "algorithm = bp\n"
            "[scenario]\n"
            "rows = 2\n"
            "cols = 2\n"
            "[sweep]\n"
            "spacing = 1, 2\n");
  RunOptions options;
  options.experiment_path = (dir.work() / "tiny.ini").string();
  options.threads = 1;
  options.output = (dir.work() / "out").string();
  const RunOutcome outcome = run_experiment(options);
  CHECK(outcome.items_total == 6);  // 2 spacings × 3 trials
  CHECK(outcome.items_written == 6);
  CHECK_FALSE(outcome.interrupted);
  const cli::CsvTable trials = cli::parse_csv(dir.read("out/trials.csv"));
  REQUIRE(trials.rows.size() == 12);  // reference and bp per item
  for (std::size_t r = 0; r < trials.rows.size(); ++r) {
    CHECK(trials.at(r, "status") == "ok");
    CHECK(trials.at(r, "algorithm") == (r % 2 == 0 ? "exact" : "bp"));
    const double error = cli::to_double(trials.at(r, "max_error"));
    if (r % 2 == 0) CHECK(error == 0.0);  // the reference against itself
    else CHECK((error >= 0.0 && error < 0.05));
  }
  CHECK(dir.exists("out/summary.csv"));
  CHECK(dir.exists("out/meta.json"));
}

}  // namespace DABENCH_TEST_FILE
