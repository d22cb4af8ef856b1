// Tests of k-best JPDA (algorithms/single_scan/kbest_jpda.hpp) against brute-force enumeration:
// exact, complete and of captured mass 1 when k covers every event; with fewer events the
// renormalised marginals of exactly the k best events, whose mass it reports.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

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

TEST_CASE("kbest-jpda: exact when k covers every event, with captured mass 1", "[kbest_jpda]") {
  RandomStream rng(42, 0, 0);
  for (int trial = 0; trial < 80; ++trial) {
    const int n = 1 + static_cast<int>(rng.uniform() * 5), m = static_cast<int>(rng.uniform() * 5);
    const SingleScanProblem problem = gated_exponential_problem(rng, n, m, 0.6);
    const SolveResult result = run_solver(*make_single_scan_solver("kbest-jpda:k=100000"), problem);
    REQUIRE(result.report.skipped.empty());
    CHECK((result.marginals - brute_force_marginals(problem).marginals).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(result.report.converged);
    CHECK(result.report.captured_mass == Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("kbest-jpda: k events are the k most probable, renormalised, and their mass", "[kbest_jpda]") {
  RandomStream rng(44, 0, 0);
  for (int trial = 0; trial < 40; ++trial) {
    SingleScanProblem problem = gated_exponential_problem(rng, 4, 4, 1.0);  // one cluster of 209 events
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
    const SolveResult result = run_solver(*make_single_scan_solver("kbest-jpda:k=" + std::to_string(k)), problem);
    REQUIRE(result.report.skipped.empty());
    CHECK((result.marginals - expected).cwiseAbs().maxCoeff() < 1e-12);
    CHECK_FALSE(result.report.converged);
    CHECK(result.report.iterations == k);
    CHECK(result.report.captured_mass == Approx(kept / total).epsilon(1e-12));
  }
  CHECK_THROWS(make_single_scan_solver("kbest-jpda:k=0"));
}

}  // namespace DABENCH_TEST_FILE
