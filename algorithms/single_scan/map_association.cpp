#include "algorithms/single_scan/map_association.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/special_values.hpp"
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

  row_dual_.assign(rows_, 0.0);
  column_dual_.assign(columns, 0.0);
  column_of_row_.assign(rows_, -1);
  row_of_column_.assign(columns, -1);
  path_row_.assign(columns, -1);
  distance_.assign(columns, kInfinity);
  settled_.assign(columns, 0);
  for (int r = 0; r < rows_; ++r) augment_row(r);

  for (int r = 0; r < rows_; ++r) {
    const int column = column_of_row_[r];
    if (column < measurement_columns_) assignment[targets[first + r]] = column_measurement_[column];
  }
}

// One shortest augmenting path from the free row `start` (Crouse 2016, Alg. 1 steps with
// sparse rows): Dijkstra over reduced costs c_ij − u_i − v_j ≥ 0, settling one column at a time
// until a free column is settled; then the dual update and the augmentation. The start row's
// own dummy column is always free and reachable, so the search always ends.
void MapAssignment::augment_row(int start) {
  frontier_.clear();
  visited_rows_.clear();
  settled_columns_.clear();
  double reached = 0.0;  // distance of the last settled column
  int row = start;
  int sink = -1;
  while (sink < 0) {
    visited_rows_.push_back(row);
    const double base = reached - row_dual_[row];
    for (int k = arc_start_[row]; k < arc_start_[row + 1]; ++k) {
      const int column = arc_column_[k];
      if (settled_[column]) continue;
      const double candidate = base + arc_cost_[k] - column_dual_[column];
      if (candidate < distance_[column]) {
        if (distance_[column] == kInfinity) frontier_.push_back(column);
        distance_[column] = candidate;
        path_row_[column] = row;
      }
    }
    // The closest unsettled column; among equals a free one, then the earliest reached.
    int best = 0;
    for (int f = 1; f < static_cast<int>(frontier_.size()); ++f) {
      const double d = distance_[frontier_[f]];
      const double b = distance_[frontier_[best]];
      if (d < b || (d == b && row_of_column_[frontier_[f]] < 0 && row_of_column_[frontier_[best]] >= 0)) best = f;
    }
    const int column = frontier_[best];
    frontier_.erase(frontier_.begin() + best);
    reached = distance_[column];
    settled_[column] = 1;
    settled_columns_.push_back(column);
    if (row_of_column_[column] < 0) {
      sink = column;
    } else {
      row = row_of_column_[column];
    }
  }

  // Dual update (keeps c − u − v ≥ 0 everywhere and = 0 on the matching).
  row_dual_[start] += reached;
  for (const int r : visited_rows_) {
    if (r != start) row_dual_[r] += reached - distance_[column_of_row_[r]];
  }
  for (const int column : settled_columns_) column_dual_[column] -= reached - distance_[column];

  // Augment along the predecessor chain.
  for (int column = sink;;) {
    const int r = path_row_[column];
    row_of_column_[column] = r;
    std::swap(column_of_row_[r], column);
    if (r == start) break;
  }

  // Reset the per-search marks of every column touched (settled or still in the frontier).
  for (const int column : settled_columns_) {
    settled_[column] = 0;
    distance_[column] = kInfinity;
  }
  for (const int column : frontier_) distance_[column] = kInfinity;
}

void MapAssociation::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  graph_.find_clusters();
  assignment_solver_.solve(problem, graph_, assignment_);
  marginals.reshape_zero(graph_.targets(), graph_.measurements());
  for (int i = 0; i < graph_.targets(); ++i) marginals(i, assignment_[i] + 1) = 1.0;
}

DABENCH_REGISTER_SINGLE_SCAN(MapAssociation);

}  // namespace dabench
