#pragma once
// The MAP association event of Williams & Lau 2014 (bp-marginal-association), eq (9): the
// feasible event a (each target takes one gated measurement or none, no measurement used
// twice) maximising Π_i ψ_i(a_i), with ψ_i(0) = 1 and side weights folded in by
// SingleScanProblem::normalized_weight (ψ_i(j) = w_ij / (w_i0 w_0j), which rescales every
// event by the same constant Π_i w_i0 Π_j w_0j and so leaves the maximiser unchanged).
//
// Formulation: a rectangular linear assignment problem on costs c_ij = −log ψ_i(j). Rows are
// the targets; columns are the measurements plus one dummy column per target ("missed",
// cost −log ψ_i(0) = 0, usable by that target only). Every row is assigned exactly once;
// measurements left over are false alarms (their factor is 1 in the normalised form). Zero
// weights are absent arcs, never assigned. The joint of eq (9) factorises over the connected
// components of the gating graph (AssociationGraph clusters), so each cluster is solved on its
// own: a large sparse problem costs the sum of its small clusters.
//
// Algorithm: shortest augmenting paths with dual potentials (harness/core/
// shortest_augmenting_path.hpp, shared with the dense LinearAssignment), run over the sparse
// arc list of each row (the gated measurements plus the row's own dummy). One Dijkstra search
// per row, so O(R·(E_c + R·C)) per cluster at worst (R rows, C columns, E_c arcs), O(n³) for a
// dense n×n block. Chosen over an ε-scaling auction because it is exact for real-valued costs
// (auction is exact only once ε·n is below the gap to the second-best assignment, which real
// log-likelihoods do not bound) and needs no tuning. Costs are shifted per row to be ≥ 0
// (c_ij − min(0, min_j' c_ij'), a per-row constant that does not change the optimum), so the
// initial zero potentials are dual feasible.
//
// Ties: any maximiser, deterministically (the search order is fixed by the problem's indices;
// among equal tentative distances a free column is preferred, then the earliest reached:
// TieOrder::first_reached).
// Output of the registered algorithm `map`: 0/1 marginals of the MAP event (each row holds a
// single 1). MCMCDA (algorithms/single_scan/mcmcda.hpp) reuses MapAssignment for its initial state.
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/single_scan/association_graph.hpp"
#include "harness/core/params.hpp"
#include "harness/core/shortest_augmenting_path.hpp"
#include "harness/single_scan/solver.hpp"

namespace dabench {

// The assignment solver itself, with its workspace (no allocation once grown).
class MapAssignment {
 public:
  // `graph` was built from `problem` (with any threshold) and has find_clusters() done.
  // Fills assignment[i] = the 0-based measurement of target i in the MAP event, or -1 (missed).
  void solve(const SingleScanProblem& problem, const AssociationGraph& graph, std::vector<int>& assignment);

 private:
  void solve_cluster(const SingleScanProblem& problem, const AssociationGraph& graph, int first, int last,
                     std::vector<int>& assignment);

  // Current cluster, local indices: rows 0..R-1, columns 0..M-1 the measurements, M+r the
  // dummy ("missed") column of row r.
  int rows_ = 0;
  int measurement_columns_ = 0;
  std::vector<int> arc_start_;      // size R+1
  std::vector<int> arc_column_;
  std::vector<double> arc_cost_;    // shifted cost, ≥ 0
  std::vector<int> column_measurement_;  // local measurement column → global measurement
  std::vector<int> local_column_;   // global measurement → local column (valid where stamp matches)
  std::vector<int> column_stamp_;   // global measurement → cluster index + 1 that mapped it
  ShortestAugmentingPath<TieOrder::first_reached> search_;
};

struct MapOptions {
  void bind(ParamList&) {}
  std::string validate() const { return {}; }
};

class MapAssociation final : public SingleScanSolver {
 public:
  using Options = MapOptions;
  static constexpr std::string_view kName = "map";
  static constexpr std::string_view kSummary =
      "MAP association event (max of eq 9) by shortest augmenting paths per cluster; 0/1 marginals";

  explicit MapAssociation(const Options& options) : options_(options) {}
  void solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) override;

 private:
  Options options_;
  AssociationGraph graph_;
  MapAssignment assignment_solver_;
  std::vector<int> assignment_;
};

}  // namespace dabench
