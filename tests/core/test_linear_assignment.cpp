// Tests of harness/core/linear_assignment.hpp (shortest augmenting paths, Crouse 2016): against
// brute-force enumeration of every injection on random problems up to 7×7 (real and small-integer
// costs, negative costs, ties, forbidden +∞ entries, infeasible problems), against a bitmask
// dynamic programme on larger ones, hand-computed optima, the R > C (transposed) semantics, the
// documented tie rule, NaN/−∞ rejection, empty problems and repeated solves with one object.
// Ties are handled by comparing totals, and checking that the returned assignment is valid and
// sums to the returned total, not by comparing assignments.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "harness/core/linear_assignment.hpp"
#include "harness/core/random_stream.hpp"
#include "tests/support/cost_matrix.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

namespace {

using dabench::test::kInf;
using Problem = dabench::test::CostMatrix;

// Minimum over every injection of the smaller side into the larger of the summed cost, or +∞
// if every injection uses a forbidden entry. Plain recursion over the rows (or columns).
void enumerate(const Problem& problem, bool by_rows, int k, std::vector<char>& used, double sum, double& best) {
  const int outer = by_rows ? problem.rows : problem.cols;
  const int inner = by_rows ? problem.cols : problem.rows;
  if (k == outer) {
    best = std::min(best, sum);
    return;
  }
  for (int other = 0; other < inner; ++other) {
    if (used[other]) continue;
    const double entry = by_rows ? problem.at(k, other) : problem.at(other, k);
    if (entry == kInf) continue;
    used[other] = 1;
    enumerate(problem, by_rows, k + 1, used, sum + entry, best);
    used[other] = 0;
  }
}

double brute_force_minimum(const Problem& problem) {
  const bool by_rows = problem.rows <= problem.cols;
  std::vector<char> used(by_rows ? problem.cols : problem.rows, 0);
  double best = kInf;
  enumerate(problem, by_rows, 0, used, 0.0, best);
  return best;
}

// Minimum by dynamic programming over the set of used columns (rows taken in order), R ≤ C.
double bitmask_minimum(const Problem& problem) {
  const std::size_t masks = std::size_t{1} << problem.cols;
  std::vector<double> best(masks, kInf);
  best[0] = 0.0;
  for (std::size_t mask = 0; mask < masks; ++mask) {
    const int r = __builtin_popcountll(mask);
    if (r >= problem.rows || best[mask] == kInf) continue;
    for (int c = 0; c < problem.cols; ++c) {
      if (mask & (std::size_t{1} << c) || problem.at(r, c) == kInf) continue;
      double& target = best[mask | (std::size_t{1} << c)];
      target = std::min(target, best[mask] + problem.at(r, c));
    }
  }
  double minimum = kInf;
  for (std::size_t mask = 0; mask < masks; ++mask) {
    if (__builtin_popcountll(mask) == problem.rows) minimum = std::min(minimum, best[mask]);
  }
  return minimum;
}

// The returned assignment is a valid one of min(R, C) allowed pairs and sums to `total`.
void check_valid(const Problem& problem, const std::vector<int>& column_of_row, double total) {
  REQUIRE(static_cast<int>(column_of_row.size()) == problem.rows);
  std::vector<int> uses(problem.cols, 0);
  int assigned = 0;
  double sum = 0.0;
  for (int r = 0; r < problem.rows; ++r) {
    const int c = column_of_row[r];
    if (c < 0) {
      CHECK(c == -1);
      continue;
    }
    REQUIRE(c < problem.cols);
    CHECK(++uses[c] == 1);
    CHECK(problem.at(r, c) != kInf);
    sum += problem.at(r, c);
    ++assigned;
  }
  CHECK(assigned == std::min(problem.rows, problem.cols));
  CHECK(total == sum);  // summed in the same row order
}

// Entries: real in [-5, 5) or, with `integers`, in {-2, ..., 2} (many ties); each forbidden
// with probability `forbidden`; `single_allowed` rows keep exactly one allowed column.
Problem random_problem(RandomStream& rng, int rows, int cols, bool integers, double forbidden, bool single_allowed) {
  Problem problem{rows, cols, std::vector<double>(static_cast<std::size_t>(rows) * cols)};
  for (double& entry : problem.cost) {
    entry = integers ? std::floor(rng.uniform(-2.0, 3.0)) : rng.uniform(-5.0, 5.0);
    if (rng.uniform() < forbidden) entry = kInf;
  }
  if (single_allowed) {
    for (int r = 0; r < rows; ++r) {
      if (!rng.bernoulli(0.4)) continue;
      const int keep = std::min(cols - 1, static_cast<int>(rng.uniform() * cols));
      for (int c = 0; c < cols; ++c) {
        if (c != keep) problem.cost[static_cast<std::size_t>(r) * cols + c] = kInf;
        else if (problem.at(r, c) == kInf) problem.cost[static_cast<std::size_t>(r) * cols + c] = 1.5;
      }
    }
  }
  return problem;
}

struct Tally {
  int feasible = 0;
  int infeasible = 0;
};

void check_against_brute_force(LinearAssignment& solver, const Problem& problem, Tally& tally) {
  std::vector<int> column_of_row;
  double total = -12345.0;
  const double expected = brute_force_minimum(problem);
  const bool ok = solver.solve(problem.cost.data(), problem.rows, problem.cols, column_of_row, total);
  INFO("rows " << problem.rows << ", cols " << problem.cols << ", brute force " << expected);
  REQUIRE(ok == (expected != kInf));
  if (!ok) {
    ++tally.infeasible;
    return;
  }
  ++tally.feasible;
  check_valid(problem, column_of_row, total);
  CHECK(total == Approx(expected).margin(1e-9));
}

}  // namespace

TEST_CASE("linear assignment: hand-computed optima", "[linear_assignment]") {
  LinearAssignment solver;
  std::vector<int> column_of_row;
  double total = 0.0;

  // 3×3, unique optimum 1 + 2 + 2 = 5 (the other five permutations cost 6, 11, 9, 7, 6).
  const std::vector<double> square = {4, 1, 3,  //
                                      2, 0, 5,  //
                                      3, 2, 2};
  REQUIRE(solver.solve(square.data(), 3, 3, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{1, 0, 2});
  CHECK(total == 5.0);

  // 2×3 with negative costs: (0,1) + (1,0) = −9 beats (0,0) + (1,1) = −7 and the rest.
  const std::vector<double> wide = {-1, -5, 0,  //
                                    -4, -6, 2};
  REQUIRE(solver.solve(wide.data(), 2, 3, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{1, 0});
  CHECK(total == -9.0);

  // A forced chain: row 0 may only take column 1, which pushes row 1 (cheapest at 1) to column 2
  // and row 2 to column 0: 10 + 3 + 4 = 17.
  const std::vector<double> chain = {kInf, 10, kInf,  //
                                     kInf, 0, 3,      //
                                     4, 0, kInf};
  REQUIRE(solver.solve(chain.data(), 3, 3, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{1, 2, 0});
  CHECK(total == 17.0);
}

TEST_CASE("linear assignment: equals brute force on random problems up to 7x7", "[linear_assignment]") {
  LinearAssignment solver;  // one object throughout: state must not leak between solves
  Tally tally;
  std::uint32_t trial = 0;
  for (int cols = 1; cols <= 7; ++cols) {
    for (int rows = 1; rows <= cols; ++rows) {
      for (const double forbidden : {0.0, 0.3, 0.6}) {
        for (const bool integers : {false, true}) {
          for (const bool single_allowed : {false, true}) {
            for (int repeat = 0; repeat < 6; ++repeat) {
              RandomStream rng(2016, 1, trial++);
              check_against_brute_force(solver, random_problem(rng, rows, cols, integers, forbidden, single_allowed),
                                        tally);
            }
          }
        }
      }
    }
  }
  // Both outcomes were exercised many times.
  CHECK(tally.feasible > 1000);
  CHECK(tally.infeasible > 200);
}

TEST_CASE("linear assignment: R > C assigns every column to a distinct row, leftover rows -1",
          "[linear_assignment]") {
  LinearAssignment solver;
  std::vector<int> column_of_row;
  double total = 0.0;
  // 3×2: column 0 → row 2 (1), column 1 → row 0 (2); row 1 left over. Total 3.
  const std::vector<double> tall = {5, 2,  //
                                    4, 7,  //
                                    1, 3};
  REQUIRE(solver.solve(tall.data(), 3, 2, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{1, -1, 0});
  CHECK(total == 3.0);

  Tally tally;
  std::uint32_t trial = 0;
  for (int rows = 2; rows <= 7; ++rows) {
    for (int cols = 1; cols < rows; ++cols) {
      for (const double forbidden : {0.0, 0.5}) {
        for (int repeat = 0; repeat < 10; ++repeat) {
          RandomStream rng(2016, 2, trial++);
          check_against_brute_force(solver, random_problem(rng, rows, cols, repeat % 2 == 1, forbidden, false), tally);
        }
      }
    }
  }
  CHECK(tally.feasible > 200);
  CHECK(tally.infeasible > 5);
}

TEST_CASE("linear assignment: equals a bitmask dynamic programme on larger problems", "[linear_assignment]") {
  LinearAssignment solver;
  std::vector<int> column_of_row;
  double total = 0.0;
  for (std::uint32_t trial = 0; trial < 40; ++trial) {
    RandomStream rng(2016, 3, trial);
    const int cols = 10 + static_cast<int>(trial % 5);  // 10..14
    const int rows = cols - static_cast<int>(trial % 4);
    const Problem problem = random_problem(rng, rows, cols, trial % 2 == 1, trial % 3 == 0 ? 0.5 : 0.0, false);
    const double expected = bitmask_minimum(problem);
    INFO("trial " << trial << ", " << rows << "x" << cols << ", expected " << expected);
    REQUIRE(solver.solve(problem.cost.data(), rows, cols, column_of_row, total) == (expected != kInf));
    if (expected == kInf) continue;
    check_valid(problem, column_of_row, total);
    CHECK(total == Approx(expected).margin(1e-9));
  }
}

TEST_CASE("linear assignment: infeasible problems return false, and the object recovers", "[linear_assignment]") {
  LinearAssignment solver;
  std::vector<int> column_of_row;
  double total = 0.0;
  // A row with no allowed column.
  const std::vector<double> empty_row = {1, 2, kInf, kInf};
  CHECK_FALSE(solver.solve(empty_row.data(), 2, 2, column_of_row, total));
  // Two rows whose only allowed column is the same one.
  const std::vector<double> clash = {kInf, 3, kInf,  //
                                     kInf, 1, kInf};
  CHECK_FALSE(solver.solve(clash.data(), 2, 3, column_of_row, total));
  // Every row has an allowed column and every pair of rows can be matched, but the three rows
  // share only columns 0 and 1 (Hall's condition fails): found by the third row's search,
  // after row 1 has displaced row 0.
  const std::vector<double> hall = {1, 2, kInf, kInf,     //
                                    3, kInf, kInf, kInf,  //
                                    kInf, 4, kInf, kInf};
  CHECK_FALSE(solver.solve(hall.data(), 3, 4, column_of_row, total));
  // R > C: both columns allowed only in row 0.
  const std::vector<double> tall_clash = {1, 2, kInf, kInf, kInf, kInf};
  CHECK_FALSE(solver.solve(tall_clash.data(), 3, 2, column_of_row, total));

  // The same object then solves feasible problems exactly: 4×2, column 0 → row 1 (3), column 1 →
  // row 0 (2), total 5 (next best 7).
  const std::vector<double> tall = {1, 2,     //
                                    3, kInf,  //
                                    kInf, 9,  //
                                    5, 6};
  REQUIRE(solver.solve(tall.data(), 4, 2, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{1, 0, -1, -1});
  CHECK(total == 5.0);
  REQUIRE(solver.solve(hall.data(), 2, 4, column_of_row, total));  // rows 0 and 1 alone: 2 + 3
  CHECK(column_of_row == std::vector<int>{1, 0});
  CHECK(total == 5.0);
}

TEST_CASE("linear assignment: ties are broken by the documented rule", "[linear_assignment]") {
  LinearAssignment solver;
  std::vector<int> column_of_row;
  double total = 0.0;
  // Constant square matrix: the identity.
  const std::vector<double> constant(25, 3.0);
  REQUIRE(solver.solve(constant.data(), 5, 5, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(total == 15.0);
  // Constant wide matrix: the lowest columns, in order.
  REQUIRE(solver.solve(constant.data(), 3, 8, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{0, 1, 2});
  CHECK(total == 9.0);
  // Constant tall matrix: each column takes the lowest row free for it.
  REQUIRE(solver.solve(constant.data(), 8, 3, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{0, 1, 2, -1, -1, -1, -1, -1});
}

TEST_CASE("linear assignment: empty problems", "[linear_assignment]") {
  LinearAssignment solver;
  std::vector<int> column_of_row = {7, 7};
  double total = 1.0;
  REQUIRE(solver.solve(nullptr, 0, 0, column_of_row, total));
  CHECK(column_of_row.empty());
  CHECK(total == 0.0);
  total = 1.0;
  REQUIRE(solver.solve(nullptr, 0, 3, column_of_row, total));
  CHECK(column_of_row.empty());
  CHECK(total == 0.0);
  total = 1.0;
  REQUIRE(solver.solve(nullptr, 3, 0, column_of_row, total));
  CHECK(column_of_row == std::vector<int>{-1, -1, -1});
  CHECK(total == 0.0);
}

TEST_CASE("linear assignment: NaN, -inf and negative sizes throw", "[linear_assignment]") {
  LinearAssignment solver;
  std::vector<int> column_of_row;
  double total = 0.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> with_nan = {1, 2, 3, nan};
  CHECK_THROWS_AS(solver.solve(with_nan.data(), 2, 2, column_of_row, total), std::invalid_argument);
  CHECK_THROWS_AS(solver.solve(with_nan.data(), 4, 1, column_of_row, total), std::invalid_argument);  // tall too
  CHECK_THROWS_WITH(solver.solve(with_nan.data(), 2, 2, column_of_row, total), Catch::Contains("cost(1, 1)"));
  const std::vector<double> with_minus_inf = {1, -kInf, 3, 4};
  CHECK_THROWS_AS(solver.solve(with_minus_inf.data(), 2, 2, column_of_row, total), std::invalid_argument);
  CHECK_THROWS_AS(solver.solve(with_minus_inf.data(), -1, 2, column_of_row, total), std::invalid_argument);
  // A NaN outside the rows × cols block is not read.
  REQUIRE(solver.solve(with_nan.data(), 1, 2, column_of_row, total));
  CHECK(total == 1.0);
}

TEST_CASE("linear assignment: repeated solves with one object give identical results", "[linear_assignment]") {
  // Problems of varying shapes (wide, square, tall, infeasible), solved in turn by one object,
  // twice, and by a fresh object each: every assignment and total bit-identical.
  std::vector<Problem> problems;
  for (std::uint32_t trial = 0; trial < 60; ++trial) {
    RandomStream rng(2016, 4, trial);
    const int rows = 1 + static_cast<int>(trial % 9);
    const int cols = 1 + static_cast<int>((trial * 5) % 9);
    problems.push_back(random_problem(rng, rows, cols, trial % 2 == 0, trial % 3 == 0 ? 0.5 : 0.1, trial % 4 == 0));
  }
  struct Outcome {
    bool ok;
    std::vector<int> column_of_row;
    double total;
  };
  auto solve_all = [&](LinearAssignment& solver) {
    std::vector<Outcome> outcomes;
    for (const Problem& problem : problems) {
      Outcome outcome{false, {}, 0.0};
      outcome.ok = solver.solve(problem.cost.data(), problem.rows, problem.cols, outcome.column_of_row, outcome.total);
      outcomes.push_back(outcome);
    }
    return outcomes;
  };
  LinearAssignment reused;
  const std::vector<Outcome> first = solve_all(reused);
  const std::vector<Outcome> second = solve_all(reused);
  int feasible = 0;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    LinearAssignment fresh;
    std::vector<int> column_of_row;
    double total = 0.0;
    const bool ok = fresh.solve(problems[k].cost.data(), problems[k].rows, problems[k].cols, column_of_row, total);
    INFO("problem " << k);
    REQUIRE(first[k].ok == ok);
    REQUIRE(second[k].ok == ok);
    if (!ok) continue;
    ++feasible;
    CHECK(first[k].column_of_row == column_of_row);
    CHECK(second[k].column_of_row == column_of_row);
    CHECK(first[k].total == total);
    CHECK(second[k].total == total);
  }
  CHECK(feasible > 20);
}

}  // namespace DABENCH_TEST_FILE
