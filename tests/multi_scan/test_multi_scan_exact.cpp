// Tests of `ms-exact`, the exact multiple-scan posterior (multiscan-convex-variational eqs 1-4),
// against hand-computed cases and against the brute-force joint enumeration of
// tests/support/multi_scan.hpp, which shares no code with it.
#include <catch2/catch.hpp>

#include "tests/support/multi_scan.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

MultiScanProblem one_scan(std::vector<Vector> prior, std::vector<RowMatrix> factor) {
  MultiScanProblem problem;
  problem.prior = std::move(prior);
  ScanFactors scan;
  scan.measurements = static_cast<int>(factor[0].cols()) - 1;
  scan.factor = std::move(factor);
  problem.scans.push_back(scan);
  return problem;
}

}  // namespace

TEST_CASE("ms-exact: one track is the product of its factors") {
  // q(A) ∝ ψ(A) Σ_a ψ_1(A, a); q^{1,j} ∝ Σ_A ψ(A) ψ_1(A, j).
  Vector prior(2);
  prior << 1.0, 3.0;
  RowMatrix factor(2, 2);
  factor << 0.5, 1.5,
            1.0, 1.0;
  const MultiScanRun run = run_multi_scan("ms-exact", one_scan({prior}, {factor}));
  REQUIRE(run.report.skipped.empty());
  // A: 1·2 = 2, 3·2 = 6 → 1/4, 3/4.  a: 0.5 + 3 = 3.5, 1.5 + 3 = 4.5 → 3.5/8, 4.5/8.
  CHECK(run.beliefs.track[0][0] == Approx(0.25).margin(1e-15));
  CHECK(run.beliefs.track[0][1] == Approx(0.75).margin(1e-15));
  CHECK(run.beliefs.association[0](0, 0) == Approx(3.5 / 8.0).margin(1e-15));
  CHECK(run.beliefs.association[0](0, 1) == Approx(4.5 / 8.0).margin(1e-15));
}

TEST_CASE("ms-exact: two tracks competing for one measurement") {
  // Events: both miss (w = 1·1), track 1 takes it (2·1), track 2 takes it (1·3); Z = 6.
  Vector prior = Vector::Ones(1);
  RowMatrix first(1, 2), second(1, 2);
  first << 1.0, 2.0;
  second << 1.0, 3.0;
  const MultiScanRun run = run_multi_scan("ms-exact", one_scan({prior, prior}, {first, second}));
  REQUIRE(run.report.skipped.empty());
  CHECK(run.beliefs.association[0](0, 1) == Approx(2.0 / 6.0).margin(1e-15));
  CHECK(run.beliefs.association[0](1, 1) == Approx(3.0 / 6.0).margin(1e-15));
  CHECK(run.beliefs.association[0](0, 0) == Approx(4.0 / 6.0).margin(1e-15));
  CHECK(run.beliefs.track[1][0] == Approx(1.0).margin(1e-15));
}

TEST_CASE("ms-exact: matches brute-force joint enumeration on random problems") {
  int cases = 0;
  for (int tracks : {2, 3}) {
    for (int hypotheses : {1, 3}) {
      for (const std::vector<int>& measurements : {std::vector<int>{2, 1}, std::vector<int>{1, 2, 2}}) {
        for (double zeros : {0.0, 0.4}) {
          const std::uint64_t seed = 100 + static_cast<std::uint64_t>(cases++);
          const MultiScanProblem problem = random_multi_scan_problem({tracks, hypotheses, measurements, zeros}, seed);
          const MultiScanRun run = run_multi_scan("ms-exact", problem);
          REQUIRE(run.report.skipped.empty());
          const MultiScanBeliefs reference = brute_force_posterior(problem);
          INFO("tracks " << tracks << " hypotheses " << hypotheses << " scans " << measurements.size() << " zeros "
                         << zeros);
          CHECK(belief_difference(run.beliefs, reference) < 1e-13);
        }
      }
    }
  }
}

TEST_CASE("ms-exact: refuses past the work limit") {
  const MultiScanProblem problem = random_multi_scan_problem({3, 2, {3, 3, 3}, 0.0}, 5);
  const MultiScanRun limited = run_multi_scan("ms-exact:max_events=1000", problem);
  CHECK(limited.report.skipped == "work_limit");
  const MultiScanRun full = run_multi_scan("ms-exact", problem);
  CHECK(full.report.skipped.empty());
}

TEST_CASE("ms-exact: an all-zero history space is skipped not divided by zero") {
  Vector prior = Vector::Ones(1);
  RowMatrix zero = RowMatrix::Zero(1, 2);
  const MultiScanRun run = run_multi_scan("ms-exact", one_scan({prior}, {zero}));
  CHECK(run.report.skipped == "zero_partition");
}

}  // namespace DABENCH_TEST_FILE
