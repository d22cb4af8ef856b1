// The contract every registered single-scan algorithm must keep (DESIGN.md, "A contract test
// runs every registered algorithm on a tiny problem"). Iterates single_scan_algorithm_registry(), so a
// new algorithm is covered the moment it registers itself. Each algorithm is built with its
// defaults (entry.create({})) and, on a fixed set of small problems including degenerate ones,
// either refuses (report.skipped non-empty) or returns:
//   - a table of shape n×(m+1) whose entries are finite and in [0, 1],
//   - rows summing to 1 within 1e-9 (also on weights spanning more than double's range),
//   - p(i, j) == 0 exactly wherever ψ_i(j) == 0 (a gated-out pair is impossible),
// and results that depend only on the problem: bit-identical from a fresh solver, from a solver
// that solved other problems in between (workspace reuse), and into a reused output table.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using namespace dabench::test;

namespace {

struct NamedProblem {
  std::string name;
  SingleScanProblem problem;
};

SingleScanProblem from_psi(const RowMatrix& psi) {
  SingleScanProblem problem;
  problem.psi = psi;
  return problem;
}

std::vector<NamedProblem> contract_problems() {
  std::vector<NamedProblem> problems;
  RandomStream rng(424242, 0, 0);
  problems.push_back({"0 targets x 3 measurements", from_psi(RowMatrix::Zero(0, 3))});
  problems.push_back({"3 targets x 0 measurements", from_psi(RowMatrix::Zero(3, 0))});
  problems.push_back({"0 x 0", from_psi(RowMatrix::Zero(0, 0))});
  problems.push_back({"1 x 1", from_psi(RowMatrix::Constant(1, 1, 2.5))});
  problems.push_back({"all-zero 3 x 4", from_psi(RowMatrix::Zero(3, 4))});
  problems.push_back({"dense 4 x 4", random_problem(rng, 4, 4, Density::dense)});
  problems.push_back({"sparse 5 x 6", random_problem(rng, 5, 6, Density::sparse)});
  problems.push_back({"extreme 5 x 5", random_problem(rng, 5, 5, Density::extreme)});
  {
    SingleScanProblem p = random_problem(rng, 4, 3, Density::dense);
    p.psi(2, 1) = 1e6;
    problems.push_back({"one huge weight 4 x 3", p});
  }
  problems.push_back({"side weights, sparse 3 x 4", random_problem(rng, 3, 4, Density::sparse, true)});
  {
    SingleScanProblem p = from_psi(RowMatrix::Zero(2, 2));
    p.miss_weight = Vector::Constant(2, 3.0);
    p.clutter_weight = Vector::Constant(2, 0.5);
    problems.push_back({"all-zero with side weights 2 x 2", p});
  }
  problems.push_back({"more measurements than targets 2 x 7", random_problem(rng, 2, 7, Density::dense)});
  problems.push_back({"more targets than measurements 7 x 2", random_problem(rng, 7, 2, Density::dense)});
  // Weights beyond double's range within one event (found by tests/fuzz/fuzz_weights): the plain
  // message s − ψν of BP cancels to 0, row-scaled products underflow. Refusing is allowed.
  problems.push_back({"psi 1e20 shared by 5 targets", from_psi(RowMatrix::Constant(5, 1, 1e20))});
  problems.push_back({"psi 1e30 gated by 12 targets", from_psi(RowMatrix::Constant(12, 1, 1e30))});
  {
    RowMatrix psi(6, 3);
    psi << 150, 1e300, 0, 15e-150, 1e300, 0, 150, 1e300, 0, 5, 0, 0, 5, 0, 0, 0, 0, 7.5;
    problems.push_back({"1e300 beside 1e-149 (fuzz finding)", from_psi(psi)});
  }
  for (const NamedProblem& p : problems) REQUIRE(p.problem.validate().empty());
  return problems;
}

struct Outcome {
  RowMatrix marginals;
  SolveReport report;
};

// Solves into `table` after poisoning every slot it could reuse with NaN, so an entry the
// solver forgets to write shows up as non-finite.
Outcome solve_into(SingleScanSolver& solver, const SingleScanProblem& problem, MarginalTable& table) {
  table.reshape(16, 16);
  table.view().setConstant(std::numeric_limits<double>::quiet_NaN());
  Outcome outcome;
  outcome.report.skipped = "stale";  // a solver must set the report, not inherit it
  outcome.report.iterations = -7;
  solver.solve(problem, table, outcome.report);
  if (outcome.report.skipped.empty()) outcome.marginals = to_matrix(table);
  return outcome;
}

bool bit_identical(const Outcome& a, const Outcome& b) {
  if (a.report.skipped != b.report.skipped) return false;
  if (a.report.iterations != b.report.iterations || a.report.converged != b.report.converged) return false;
  if (std::memcmp(&a.report.w_star, &b.report.w_star, sizeof(double)) != 0) return false;
  if (a.marginals.rows() != b.marginals.rows() || a.marginals.cols() != b.marginals.cols()) return false;
  return a.marginals.size() == 0 ||
         std::memcmp(a.marginals.data(), b.marginals.data(), sizeof(double) * a.marginals.size()) == 0;
}

}  // namespace

TEST_CASE("contract: the registry holds the baseline algorithms", "[contract]") {
  const auto& entries = single_scan_algorithm_registry().entries();
  CHECK(entries.count("bp") == 1);
  CHECK(entries.count("exact") == 1);
  for (const auto& [name, entry] : entries) {
    CHECK(name == entry.name);
    CHECK_FALSE(entry.summary.empty());
  }
}

TEST_CASE("contract: every algorithm returns valid marginals", "[contract]") {
  const std::vector<NamedProblem> problems = contract_problems();
  for (const auto& [name, entry] : single_scan_algorithm_registry().entries()) {
    auto solver = entry.create({});
    REQUIRE(solver != nullptr);
    MarginalTable table;
    for (const NamedProblem& named : problems) {
      const SingleScanProblem& problem = named.problem;
      const Outcome outcome = solve_into(*solver, problem, table);
      INFO("algorithm " << name << ", problem " << named.name);
      CHECK(outcome.report.skipped != "stale");
      if (!outcome.report.skipped.empty()) continue;  // refused: allowed, recorded as skipped:<reason>
      CHECK(outcome.report.iterations >= 0);
      const int n = problem.targets();
      const int m = problem.measurements();
      REQUIRE(table.targets() == n);
      REQUIRE(table.measurements() == m);
      for (int i = 0; i < n; ++i) {
        double row_sum = 0.0;
        for (int j = 0; j <= m; ++j) {
          const double p = outcome.marginals(i, j);
          INFO("entry (" << i << ", " << j << ") = " << p);
          REQUIRE(std::isfinite(p));
          CHECK(p >= 0.0);
          CHECK(p <= 1.0);
          row_sum += p;
          if (j > 0 && problem.psi(i, j - 1) == 0.0) CHECK(p == 0.0);
        }
        INFO("row " << i);
        CHECK(row_sum == Approx(1.0).epsilon(0).margin(1e-9));
      }
    }
  }
}

TEST_CASE("contract: results depend only on the problem (bit-identical)", "[contract]") {
  const std::vector<NamedProblem> problems = contract_problems();
  for (const auto& [name, entry] : single_scan_algorithm_registry().entries()) {
    INFO("algorithm " << name);
    // Reference: one fresh solver and one fresh table per problem.
    std::vector<Outcome> fresh;
    for (const NamedProblem& named : problems) {
      auto solver = entry.create({});
      MarginalTable table;
      fresh.push_back(solve_into(*solver, named.problem, table));
    }
    // A second fresh solver per problem gives the same bits.
    for (std::size_t k = 0; k < problems.size(); ++k) {
      auto solver = entry.create({});
      MarginalTable table;
      INFO("problem " << problems[k].name << " (second fresh solver)");
      CHECK(bit_identical(solve_into(*solver, problems[k].problem, table), fresh[k]));
    }
    // One solver and one table for the whole list, twice over, forwards then backwards: every
    // problem is solved after problems of other shapes (A, B, ..., A again).
    auto reused = entry.create({});
    MarginalTable table;
    std::vector<std::size_t> order;
    for (std::size_t k = 0; k < problems.size(); ++k) order.push_back(k);
    for (std::size_t k = problems.size(); k-- > 0;) order.push_back(k);
    for (std::size_t k = 0; k < problems.size(); ++k) order.push_back(k);
    for (const std::size_t k : order) {
      INFO("problem " << problems[k].name << " (reused solver and table)");
      CHECK(bit_identical(solve_into(*reused, problems[k].problem, table), fresh[k]));
    }
    // The explicit A, B, A sequence with B larger than A.
    const Outcome a1 = solve_into(*reused, problems[5].problem, table);  // dense 4 x 4
    const Outcome b = solve_into(*reused, problems[6].problem, table);   // sparse 5 x 6
    const Outcome a2 = solve_into(*reused, problems[5].problem, table);
    CHECK(bit_identical(a1, a2));
    CHECK(bit_identical(b, fresh[6]));
    CHECK(bit_identical(a1, fresh[5]));
  }
}

}  // namespace DABENCH_TEST_FILE
