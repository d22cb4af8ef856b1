// Tests of the single-target row of algorithms/single_scan/association_graph.hpp
// (write_normalized_row): p(a_i = 0) = 1/Z, p(a_i = j) = ψ_i(j)/Z, Z = 1 + Σ_j ψ_i(j), by hand;
// no overflow for huge weights; weights below the floor left out; and the algorithms that use it
// for a target alone in its cluster (ehm, jt) give its row bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <string>

#include "algorithms/single_scan/association_graph.hpp"
#include "algorithms/single_scan/ehm.hpp"
#include "algorithms/single_scan/junction_tree.hpp"
#include "harness/single_scan/registry.hpp"
#include "tests/support/brute_force.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

namespace {

// Targets 0 and 1 share measurement 1; target 2 is alone (measurements 2 and 3).
SingleScanProblem three_targets() {
  SingleScanProblem problem;
  problem.psi = RowMatrix(3, 4);
  problem.psi << 0.5, 2.0, 0.0, 0.0,  //
      0.0, 1.5, 0.0, 0.0,             //
      0.0, 0.0, 3.0, 0.25;
  return problem;
}

}  // namespace

TEST_CASE("association graph: a target's row is psi / (1 + sum psi), by hand", "[association_graph]") {
  AssociationGraph graph;
  graph.build(three_targets());
  MarginalTable table;
  table.reshape_zero(3, 4);
  const RowNormalizer z = write_normalized_row(graph, 2, graph.edge_weights(), table.row(2));
  CHECK(table(2, 0) == Approx(1.0 / 4.25).epsilon(1e-15));
  CHECK(table(2, 3) == Approx(3.0 / 4.25).epsilon(1e-15));
  CHECK(table(2, 4) == Approx(0.25 / 4.25).epsilon(1e-15));
  CHECK(table(2, 1) == 0.0);  // ungated entries untouched
  CHECK(z.largest == 3.0);
  CHECK(z.largest * z.total == Approx(4.25).epsilon(1e-15));
  // Row 0 of the table is not written by row 2's call.
  CHECK(table(0, 0) == 0.0);
}

TEST_CASE("association graph: huge weights do not overflow the row", "[association_graph]") {
  SingleScanProblem problem;
  problem.psi = RowMatrix(1, 3);
  problem.psi << 1e300, 1e300, 1.0;
  AssociationGraph graph;
  graph.build(problem);
  MarginalTable table;
  table.reshape_zero(1, 3);
  const RowNormalizer z = write_normalized_row(graph, 0, graph.edge_weights(), table.row(0));
  CHECK(table(0, 1) == Approx(0.5).epsilon(1e-15));
  CHECK(table(0, 2) == Approx(0.5).epsilon(1e-15));
  CHECK(table(0, 0) == Approx(0.5e-300).epsilon(1e-12));
  CHECK(table(0, 3) == Approx(0.5e-300).epsilon(1e-12));
  CHECK(std::log(z.largest) + std::log(z.total) == Approx(std::log(2.0) + 300.0 * std::log(10.0)).epsilon(1e-15));
}

TEST_CASE("association graph: weights below the floor are left out of the row", "[association_graph]") {
  AssociationGraph graph;
  graph.build(three_targets());
  MarginalTable table;
  table.reshape_zero(3, 4);
  table(2, 4) = -1.0;  // marks an entry the call must not touch
  write_normalized_row(graph, 2, graph.edge_weights(), table.row(2), 0.5);
  CHECK(table(2, 0) == Approx(1.0 / 4.0).epsilon(1e-15));
  CHECK(table(2, 3) == Approx(3.0 / 4.0).epsilon(1e-15));
  CHECK(table(2, 4) == -1.0);
}

TEST_CASE("association graph: ehm and jt write a lone target's row with it", "[association_graph]") {
  const SingleScanProblem problem = three_targets();
  AssociationGraph graph;
  graph.build(problem);
  MarginalTable expected;
  expected.reshape_zero(3, 4);
  write_normalized_row(graph, 2, graph.edge_weights(), expected.row(2));
  for (const std::string spec : {"ehm", "ehm:tree=0", "jt", "jt:threshold_on=2,threshold=0.01"}) {
    INFO(spec);
    auto solver = make_single_scan_solver(spec);
    const test::SolveResult result = test::run_solver(*solver, problem);
    REQUIRE(result.report.skipped.empty());
    for (int j = 0; j <= 4; ++j) CHECK(result.marginals(2, j) == expected(2, j));  // bit for bit
  }
  Ehm ehm{EhmOptions{}};
  test::run_solver(ehm, problem);
  JunctionTree jt{JtOptions{}};
  test::run_solver(jt, problem);
  // log Z: the pair's (1 + 0.5 + 2 + 1.5 + 0.5·1.5 = 5.75, as ψ_01 ψ_11 is excluded) plus the lone target's.
  const double log_z = std::log(1.0 + 0.5 + 2.0 + 1.5 + 0.5 * 1.5) + std::log(4.25);
  CHECK(ehm.stats().log_partition == Approx(log_z).epsilon(1e-14));
  CHECK(jt.log_partition() == Approx(log_z).epsilon(1e-14));
}

}  // namespace DABENCH_TEST_FILE
