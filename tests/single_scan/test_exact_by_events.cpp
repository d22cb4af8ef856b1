// Tests of the exact permanent (algorithms/single_scan/permanent.hpp) and of k-best JPDA
// (algorithms/single_scan/kbest_jpda.hpp) against brute-force enumeration: the permanent to
// 1e-12 on random problems of either shape (more targets or more measurements) and on several
// clusters; k-best JPDA exact, complete and of captured mass 1 when k covers every event, and
// with fewer events the renormalised marginals of exactly the k best events, whose mass it reports.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

SingleScanProblem random_problem(RandomStream& rng, int n, int m, double gated) {
  SingleScanProblem problem;
  problem.psi = RowMatrix::Zero(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      if (rng.uniform() < gated) problem.psi(i, j) = -3.0 * std::log(1.0 - rng.uniform());
    }
  }
  return problem;
}

SolveResult solve(const std::string& spec, const SingleScanProblem& problem) {
  auto solver = make_single_scan_solver(spec);
  return run_solver(*solver, problem);
}

// Every event with its weight, by enumeration (the test's own).
struct Event {
  std::vector<int> measurement;  // per target, 0 = missed
  double weight;
};
void enumerate(const RowMatrix& psi, int i, std::vector<int>& current, std::vector<char>& used, double weight,
               std::vector<Event>& out) {
  if (i == psi.rows()) {
    out.push_back({current, weight});
    return;
  }
  current[i] = 0;
  enumerate(psi, i + 1, current, used, weight, out);
  for (int j = 0; j < psi.cols(); ++j) {
    if (used[j] || psi(i, j) == 0.0) continue;
    used[j] = 1;
    current[i] = j + 1;
    enumerate(psi, i + 1, current, used, weight * psi(i, j), out);
    used[j] = 0;
  }
}

}  // namespace

TEST_CASE("permanent: equals enumeration on random problems of either shape", "[permanent]") {
  RandomStream rng(41, 0, 0);
  double worst = 0.0;
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 1 + static_cast<int>(rng.uniform() * 6), m = static_cast<int>(rng.uniform() * 7);
    const SingleScanProblem problem = random_problem(rng, n, m, trial % 2 == 0 ? 1.0 : 0.4);
    const SolveResult result = solve("permanent", problem);
    REQUIRE(result.report.skipped.empty());
    worst = std::max(worst, (result.marginals - brute_force_marginals(problem).marginals).cwiseAbs().maxCoeff());
  }
  CHECK(worst < 1e-12);
}

TEST_CASE("permanent: huge and tiny weights, and the memory limit", "[permanent]") {
  SingleScanProblem problem;
  problem.psi = RowMatrix(3, 3);
  problem.psi << 1e100, 1e-100, 3,  // events up to 1e300: the brute force's products stay finite
                 2, 1e100, 1e-80,
                 1e50, 5, 1e100;
  const SolveResult result = solve("permanent", problem);
  REQUIRE(result.report.skipped.empty());
  CHECK((result.marginals - brute_force_marginals(problem).marginals).cwiseAbs().maxCoeff() < 1e-12);
  RandomStream rng(43, 0, 0);
  const SingleScanProblem big = random_problem(rng, 24, 24, 1.0);  // 27 · 2^24 doubles: 3.4 GiB
  CHECK(solve("permanent:memory_mb=1024", big).report.skipped == "memory");
}

TEST_CASE("permanent: refuses where underflow in its scaled layers could move a probability", "[permanent]") {
  // A fuzzer's find: targets 2 and 3 are identical, so their marginals must be; the product of a
  // scaled forward entry (1e-30, target 1's ψ of 1e30 ahead of it) and a scaled backward entry
  // (2e-300, target 3's 1e300 behind it) underflows, and without the bound the permanent gave
  // target 2 a missed-detection probability of 0.994 against the exact 0.497.
  SingleScanProblem problem;
  problem.psi = RowMatrix(3, 3);
  problem.psi << 170, 1e30, 0,
                 1, 1e300, 0,
                 1, 1e300, 0;
  const SolveResult result = solve("permanent", problem);
  CHECK(result.report.skipped == "numerical");
  const SolveResult kept = solve("kbest-jpda:k=100", problem);  // the events' weights stay relative to the best
  REQUIRE(kept.report.skipped.empty());
  CHECK(kept.marginals(1, 0) == Approx(kept.marginals(2, 0)).epsilon(1e-12));
}

TEST_CASE("kbest-jpda: exact when k covers every event, with captured mass 1", "[kbest_jpda]") {
  RandomStream rng(42, 0, 0);
  for (int trial = 0; trial < 80; ++trial) {
    const int n = 1 + static_cast<int>(rng.uniform() * 5), m = static_cast<int>(rng.uniform() * 5);
    const SingleScanProblem problem = random_problem(rng, n, m, 0.6);
    const SolveResult result = solve("kbest-jpda:k=100000", problem);
    REQUIRE(result.report.skipped.empty());
    CHECK((result.marginals - brute_force_marginals(problem).marginals).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(result.report.converged);
    CHECK(result.report.captured_mass == Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("kbest-jpda: k events are the k most probable, renormalised, and their mass", "[kbest_jpda]") {
  RandomStream rng(44, 0, 0);
  for (int trial = 0; trial < 40; ++trial) {
    SingleScanProblem problem = random_problem(rng, 4, 4, 1.0);  // one cluster of 209 events
    std::vector<Event> events;
    std::vector<int> current(4);
    std::vector<char> used(4, 0);
    enumerate(problem.psi, 0, current, used, 1.0, events);
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.weight > b.weight; });
    const int k = 1 + trial % 12;
    RowMatrix expected = RowMatrix::Zero(4, 5);
    double kept = 0.0, total = 0.0;
    for (std::size_t e = 0; e < events.size(); ++e) {
      total += events[e].weight;
      if (static_cast<int>(e) >= k) continue;
      kept += events[e].weight;
      for (int i = 0; i < 4; ++i) expected(i, events[e].measurement[static_cast<std::size_t>(i)]) += events[e].weight;
    }
    expected /= kept;
    const SolveResult result = solve("kbest-jpda:k=" + std::to_string(k), problem);
    REQUIRE(result.report.skipped.empty());
    CHECK((result.marginals - expected).cwiseAbs().maxCoeff() < 1e-12);
    CHECK_FALSE(result.report.converged);
    CHECK(result.report.iterations == k);
    CHECK(result.report.captured_mass == Approx(kept / total).epsilon(1e-12));
  }
  CHECK_THROWS(make_single_scan_solver("kbest-jpda:k=0"));
}

}  // namespace DABENCH_TEST_FILE
