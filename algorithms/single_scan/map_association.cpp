#include "algorithms/single_scan/map_association.hpp"

#include <algorithm>
#include <cmath>

#include "harness/single_scan/registry.hpp"

namespace dabench {

namespace {

// log ψ_i(j) in the ψ_i(0) = 1 normalisation, computed in the log domain so that side weights
// cannot overflow or underflow the ratio w_ij / (w_i0 w_0j).
inline double log_weight(const SingleScanProblem& problem, int i, int j) {
  double value = std::log(problem.psi(i, j));
  if (problem.miss_weight.size() != 0) value -= std::log(problem.miss_weight[i]);
  if (problem.clutter_weight.size() != 0) value -= std::log(problem.clutter_weight[j]);
  return value;
}

}  // namespace

void MapAssignment::solve(const SingleScanProblem& problem, const AssociationGraph& graph,
                          std::vector<int>& assignment) {
  const int n = graph.targets();
  assignment.assign(n, -1);
  if (static_cast<int>(column_stamp_.size()) < graph.measurements()) {
    column_stamp_.resize(graph.measurements(), 0);
    local_column_.resize(graph.measurements(), 0);
  }
  std::fill(column_stamp_.begin(), column_stamp_.begin() + graph.measurements(), 0);
  for (int c = 0; c < graph.clusters(); ++c) {
    solve_cluster(problem, graph, graph.cluster_start(c), graph.cluster_start(c + 1), assignment);
  }
}

void MapAssignment::solve_cluster(const SingleScanProblem& problem, const AssociationGraph& graph, int first,
                                  int last, std::vector<int>& assignment) {
  const std::vector<int>& targets = graph.cluster_targets();
  if (last - first == 1) {
    // One target: the best gated measurement if it beats the missed detection (ψ > 1).
    const int i = targets[first];
    double best = 0.0;
    for (int e = graph.row_begin(i); e < graph.row_end(i); ++e) {
      const double value = log_weight(problem, i, graph.edge_measurement(e));
      if (value > best) {
        best = value;
        assignment[i] = graph.edge_measurement(e);
      }
    }
    return;
  }

  // Local numbering and the sparse arc lists, costs shifted per row to be ≥ 0.
  const int stamp = first + 1;  // distinct per cluster within one solve
  rows_ = last - first;
  measurement_columns_ = 0;
  column_measurement_.clear();
  for (int r = 0; r < rows_; ++r) {
    const int i = targets[first + r];
    for (int e = graph.row_begin(i); e < graph.row_end(i); ++e) {
      const int j = graph.edge_measurement(e);
      if (column_stamp_[j] != stamp) {
        column_stamp_[j] = stamp;
        local_column_[j] = measurement_columns_++;
        column_measurement_.push_back(j);
      }
    }
  }
  const int columns = measurement_columns_ + rows_;
  arc_start_.resize(rows_ + 1);
  arc_column_.clear();
  arc_cost_.clear();
  arc_start_[0] = 0;
  for (int r = 0; r < rows_; ++r) {
    const int i = targets[first + r];
    const int begin = static_cast<int>(arc_cost_.size());
    double lowest = 0.0;  // the dummy arc's cost, −log ψ_i(0) = 0
    for (int e = graph.row_begin(i); e < graph.row_end(i); ++e) {
      const int j = graph.edge_measurement(e);
      const double cost = -log_weight(problem, i, j);
      arc_column_.push_back(local_column_[j]);
      arc_cost_.push_back(cost);
      lowest = std::min(lowest, cost);
    }
    arc_column_.push_back(measurement_columns_ + r);
    arc_cost_.push_back(0.0);
    for (int k = begin; k < static_cast<int>(arc_cost_.size()); ++k) arc_cost_[k] -= lowest;
    arc_start_[r + 1] = static_cast<int>(arc_cost_.size());
  }

  // Zero potentials are dual feasible on the shifted costs. The start row's own dummy column is
  // always free and reachable, so every search succeeds.
  search_.reset(rows_, columns);
  const auto sparse_row = [this](int row, auto&& relax) {
    for (int k = arc_start_[row]; k < arc_start_[row + 1]; ++k) relax(arc_column_[k], arc_cost_[k]);
  };
  for (int r = 0; r < rows_; ++r) {
    [[maybe_unused]] const bool matched = search_.augment(r, sparse_row);
  }

  for (int r = 0; r < rows_; ++r) {
    const int column = search_.column_of_row(r);
    if (column < measurement_columns_) assignment[targets[first + r]] = column_measurement_[column];
  }
}

void MapAssociation::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  graph_.find_clusters();
  assignment_solver_.solve(problem, graph_, assignment_);
  marginals.reshape_zero(graph_.targets(), graph_.measurements());
  for (int i = 0; i < graph_.targets(); ++i) marginals(i, assignment_[i] + 1) = 1.0;
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(MapAssociation);

}  // namespace dabench
