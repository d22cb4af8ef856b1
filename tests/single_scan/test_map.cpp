// Tests of the `map` algorithm (MAP association event of eq (9) of Williams & Lau 2014 by
// shortest augmenting paths per cluster): against hand-computed events, against a brute-force
// maximum over every feasible event (tests/support/brute_force.hpp conventions, general form
// with side weights), against a bitmask dynamic programme on clusters too large to enumerate,
// and on a large block-diagonal problem against per-block brute force. Ties are handled by
// comparing the value Π w of the returned event with the maximum, not the events themselves.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "algorithms/single_scan/map_association.hpp"
#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

// log of the general-form weight of event a (a[i] = 0-based measurement or -1), as in
// brute_force.hpp: Π_i w(i, a_i) · Π_{j unused} w_0j. -inf if a uses a zero weight.
double log_event_weight(const SingleScanProblem& problem, const std::vector<int>& a) {
  double value = 0.0;
  std::vector<char> used(problem.measurements(), 0);
  for (int i = 0; i < problem.targets(); ++i) {
    if (a[i] < 0) {
      value += std::log(miss_weight_of(problem, i));
    } else {
      value += std::log(problem.psi(i, a[i]));
      used[a[i]] = 1;
    }
  }
  for (int j = 0; j < problem.measurements(); ++j) {
    if (!used[j]) value += std::log(clutter_weight_of(problem, j));
  }
  return value;
}

// Brute-force MAP value: max over every consistent tuple in {0..m}^n of log w(a) (the
// odometer of brute_force.hpp, summing precomputed logs so extreme weights cannot overflow).
double brute_force_map_log_value(const SingleScanProblem& problem) {
  const int n = problem.targets();
  const int m = problem.measurements();
  RowMatrix log_w(n, m + 1);  // column 0: log w_i0; column j: log ψ_i(j-1) (-inf if zero)
  for (int i = 0; i < n; ++i) {
    log_w(i, 0) = std::log(miss_weight_of(problem, i));
    for (int j = 0; j < m; ++j) log_w(i, j + 1) = std::log(problem.psi(i, j));
  }
  std::vector<double> log_clutter(m + 1, 0.0);
  for (int j = 0; j < m; ++j) log_clutter[j + 1] = std::log(clutter_weight_of(problem, j));
  double all_clutter = 0.0;
  for (int j = 1; j <= m; ++j) all_clutter += log_clutter[j];
  std::vector<int> digits(n, 0);
  std::vector<int> uses(m + 1, 0);
  double best = -std::numeric_limits<double>::infinity();
  while (true) {
    std::fill(uses.begin(), uses.end(), 0);
    bool consistent = true;
    double value = all_clutter;
    for (int i = 0; i < n; ++i) {
      if (digits[i] > 0 && ++uses[digits[i]] > 1) consistent = false;
      value += log_w(i, digits[i]) - log_clutter[digits[i]];
    }
    if (consistent) best = std::max(best, value);
    int digit = 0;
    while (digit < n && digits[digit] == m) digits[digit++] = 0;
    if (digit == n) break;
    ++digits[digit];
  }
  return best;
}

// Independent exact MAP for m ≤ ~16: dynamic programme over targets with the set of used
// measurements as a bitmask.
double bitmask_map_log_value(const SingleScanProblem& problem) {
  const int n = problem.targets();
  const int m = problem.measurements();
  const double minus_inf = -std::numeric_limits<double>::infinity();
  std::vector<double> best(std::size_t{1} << m, minus_inf), next(best.size());
  best[0] = 0.0;
  for (int i = 0; i < n; ++i) {
    std::fill(next.begin(), next.end(), minus_inf);
    for (std::size_t mask = 0; mask < best.size(); ++mask) {
      if (best[mask] == minus_inf) continue;
      next[mask] = std::max(next[mask], best[mask] + std::log(miss_weight_of(problem, i)));
      for (int j = 0; j < m; ++j) {
        if ((mask >> j) & 1u || problem.psi(i, j) <= 0.0) continue;
        const std::size_t to = mask | (std::size_t{1} << j);
        next[to] = std::max(next[to], best[mask] + std::log(problem.psi(i, j)));
      }
    }
    best.swap(next);
  }
  double result = minus_inf;
  for (std::size_t mask = 0; mask < best.size(); ++mask) {
    if (best[mask] == minus_inf) continue;
    double value = best[mask];
    for (int j = 0; j < m; ++j) {
      if (!((mask >> j) & 1u)) value += std::log(clutter_weight_of(problem, j));
    }
    result = std::max(result, value);
  }
  return result;
}

// Reads the event out of 0/1 marginals, checking they are 0/1 with one 1 per row, that no
// measurement is used twice and that no zero weight is used.
std::vector<int> event_of(const SingleScanProblem& problem, const RowMatrix& marginals) {
  const int n = problem.targets();
  const int m = problem.measurements();
  REQUIRE(marginals.rows() == n);
  REQUIRE(marginals.cols() == m + 1);
  std::vector<int> a(n, -1);
  std::vector<int> uses(m, 0);
  for (int i = 0; i < n; ++i) {
    int ones = 0;
    for (int j = 0; j <= m; ++j) {
      const double p = marginals(i, j);
      REQUIRE((p == 0.0 || p == 1.0));
      if (p == 1.0) {
        ++ones;
        a[i] = j - 1;
      }
    }
    REQUIRE(ones == 1);
    if (a[i] >= 0) {
      REQUIRE(problem.psi(i, a[i]) > 0.0);
      REQUIRE(++uses[a[i]] == 1);
    }
  }
  return a;
}

RowMatrix solve_map(const SingleScanProblem& problem) {
  auto solver = make_single_scan_solver("map");
  const SolveResult result = run_solver(*solver, problem);
  REQUIRE(result.report.skipped.empty());
  return result.marginals;
}

void check_value(double found, double best) {
  INFO("log value found " << found << ", best " << best);
  CHECK(std::fabs(found - best) <= 1e-9 * std::max(1.0, std::fabs(best)));
}

}  // namespace

TEST_CASE("map: hand-computed 2x2", "[map]") {
  // ψ = [[1, 2], [3, 4]]: event weights (0,0) 1, (1,0) 1, (2,0) 2, (0,1) 3, (0,2) 4, (1,2) 4,
  // (2,1) 6 → MAP is target 1 → measurement 2, target 2 → measurement 1.
  RowMatrix expected(2, 3);
  expected << 0, 0, 1, 0, 1, 0;
  CHECK(solve_map(make_problem(psi_2x2())) == expected);
}

TEST_CASE("map: weights below one leave every target missed", "[map]") {
  RowMatrix psi(3, 4);
  psi << 0.9, 0.5, 0, 0.99, 0.2, 0.999, 0.3, 0, 0, 0, 0.01, 0.5;
  RowMatrix expected = RowMatrix::Zero(3, 5);
  expected.col(0).setOnes();
  CHECK(solve_map(make_problem(psi)) == expected);
}

TEST_CASE("map: side weights change the maximiser", "[map]") {
  // ψ = [[3]] alone: associate (3 > 1). With w_10 = 2 and w_01 = 2: associate weighs 3,
  // miss weighs w_10 · w_01 = 4, so the MAP event is the miss.
  SingleScanProblem problem = make_problem(RowMatrix::Constant(1, 1, 3.0));
  CHECK(solve_map(problem)(0, 1) == 1.0);
  problem.miss_weight = Vector::Constant(1, 2.0);
  problem.clutter_weight = Vector::Constant(1, 2.0);
  CHECK(solve_map(problem)(0, 0) == 1.0);
  // Two targets competing for one measurement: the larger normalised weight wins.
  SingleScanProblem two = make_problem((RowMatrix(2, 1) << 6.0, 4.0).finished());
  two.miss_weight = (Vector(2) << 3.0, 1.0).finished();  // normalised ψ: 2 and 4
  CHECK(solve_map(two) == (RowMatrix(2, 2) << 1, 0, 0, 1).finished());
}

TEST_CASE("map: equals brute-force MAP value on random problems", "[map]") {
  RandomStream rng(20240601, 0, 0);
  int checked = 0;
  for (int k = 0; k < 360; ++k) {
    const int n = uniform_int(rng, 0, 7);
    const int m = uniform_int(rng, 0, 7);
    const Density density = static_cast<Density>(k % 3);
    const bool side = k % 4 == 3;
    const SingleScanProblem problem = random_problem(rng, n, m, density, side);
    INFO("problem " << k << ": n=" << n << " m=" << m << " " << density_name(density) << (side ? " side" : "")
                    << "\npsi=\n" << problem.psi);
    const std::vector<int> a = event_of(problem, solve_map(problem));
    check_value(log_event_weight(problem, a), brute_force_map_log_value(problem));
    ++checked;
  }
  CHECK(checked == 360);
}

TEST_CASE("map: degenerate problems and ties", "[map]") {
  SECTION("no targets or no measurements") {
    CHECK(solve_map(make_problem(RowMatrix::Zero(0, 4))).rows() == 0);
    const RowMatrix none = solve_map(make_problem(RowMatrix::Zero(3, 0)));
    CHECK(none == RowMatrix::Ones(3, 1));
  }
  SECTION("all weights zero") {
    RowMatrix expected = RowMatrix::Zero(4, 4);
    expected.col(0).setOnes();
    CHECK(solve_map(make_problem(RowMatrix::Zero(4, 3))) == expected);
  }
  SECTION("all weights one: every event of any size ties") {
    const SingleScanProblem problem = make_problem(RowMatrix::Ones(5, 5));
    const std::vector<int> a = event_of(problem, solve_map(problem));
    check_value(log_event_weight(problem, a), 0.0);
  }
  SECTION("equal weights above one: a full matching") {
    const SingleScanProblem problem = make_problem(RowMatrix::Constant(6, 4, 2.0));
    const std::vector<int> a = event_of(problem, solve_map(problem));
    check_value(log_event_weight(problem, a), 4.0 * std::log(2.0));
  }
  SECTION("one huge weight dominates") {
    RandomStream rng(99, 0, 0);
    SingleScanProblem problem = random_problem(rng, 5, 5, Density::dense);
    problem.psi(3, 2) = 1e12;
    const std::vector<int> a = event_of(problem, solve_map(problem));
    CHECK(a[3] == 2);
    check_value(log_event_weight(problem, a), brute_force_map_log_value(problem));
  }
  SECTION("tiny and huge weights side by side") {
    RowMatrix psi(3, 3);
    psi << 1e-300, 1e300, 0, 1e300, 1e-300, 5, 0, 7, 1e-200;
    const SingleScanProblem problem = make_problem(psi);
    const std::vector<int> a = event_of(problem, solve_map(problem));
    check_value(log_event_weight(problem, a), brute_force_map_log_value(problem));
  }
}

TEST_CASE("map: dense clusters beyond enumeration match a bitmask dynamic programme", "[map]") {
  RandomStream rng(777, 0, 0);
  for (int k = 0; k < 12; ++k) {
    const int n = uniform_int(rng, 8, 13);
    const int m = uniform_int(rng, 8, 13);
    const SingleScanProblem problem = random_problem(rng, n, m, k % 2 ? Density::dense : Density::sparse, k % 3 == 0);
    INFO("problem " << k << ": n=" << n << " m=" << m);
    const std::vector<int> a = event_of(problem, solve_map(problem));
    check_value(log_event_weight(problem, a), bitmask_map_log_value(problem));
  }
}

TEST_CASE("map: large block-diagonal problem matches per-block brute force", "[map]") {
  // 40 blocks of 5 targets × 3..7 measurements (200 targets), rows and columns shuffled so
  // blocks are not contiguous; side weights on. The MAP event of the whole problem has value
  // Σ_blocks (max over the block's events), each maximum by brute force.
  RandomStream rng(31337, 0, 0);
  constexpr int kBlocks = 40;
  constexpr int kTargetsPerBlock = 5;
  std::vector<SingleScanProblem> blocks;
  int n = 0;
  int m = 0;
  for (int b = 0; b < kBlocks; ++b) {
    blocks.push_back(random_problem(rng, kTargetsPerBlock, uniform_int(rng, 3, 7),
                                    b % 2 ? Density::dense : Density::sparse, true));
    n += blocks.back().targets();
    m += blocks.back().measurements();
  }
  SingleScanProblem block_diagonal;
  block_diagonal.psi = RowMatrix::Zero(n, m);
  block_diagonal.miss_weight = Vector(n);
  block_diagonal.clutter_weight = Vector(m);
  double expected = 0.0;
  int row = 0;
  int column = 0;
  for (const SingleScanProblem& block : blocks) {
    block_diagonal.psi.block(row, column, block.targets(), block.measurements()) = block.psi;
    block_diagonal.miss_weight.segment(row, block.targets()) = block.miss_weight;
    block_diagonal.clutter_weight.segment(column, block.measurements()) = block.clutter_weight;
    expected += brute_force_map_log_value(block);
    row += block.targets();
    column += block.measurements();
  }
  const SingleScanProblem problem =
      permute_problem(block_diagonal, random_permutation(rng, n), random_permutation(rng, m));
  REQUIRE(problem.validate().empty());
  AssociationGraph graph;
  graph.build(problem);
  graph.find_clusters();
  CHECK(graph.clusters() >= kBlocks);
  const std::vector<int> a = event_of(problem, solve_map(problem));
  check_value(log_event_weight(problem, a), expected);
}

TEST_CASE("map: MapAssignment reused across problems of different shapes gives the same events", "[map]") {
  RandomStream rng(4242, 0, 0);
  std::vector<SingleScanProblem> problems;
  for (int k = 0; k < 20; ++k) {
    problems.push_back(random_problem(rng, uniform_int(rng, 1, 9), uniform_int(rng, 1, 9), static_cast<Density>(k % 3)));
  }
  MapAssignment reused;
  AssociationGraph graph;
  std::vector<int> a;
  for (int pass = 0; pass < 2; ++pass) {
    for (const SingleScanProblem& problem : problems) {
      graph.build(problem);
      graph.find_clusters();
      reused.solve(problem, graph, a);
      MapAssignment fresh;
      std::vector<int> b;
      fresh.solve(problem, graph, b);
      CHECK(a == b);
    }
  }
}

}  // namespace DABENCH_TEST_FILE
