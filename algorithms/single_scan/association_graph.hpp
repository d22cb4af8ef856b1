#pragma once
// The gating graph of a single-scan problem: the bipartite graph of eq (9) restricted to the
// pairs with ψ_i(j) > 0 (after an optional threshold), in compressed sparse rows, with its
// connected components (clusters). Shared by the algorithms that exploit gating sparsity.
#include <vector>

#include "harness/single_scan/problem.hpp"

namespace dabench {

class AssociationGraph {
 public:
  // Rebuilds from `problem` using normalised weights ψ_i(j) = w_ij / (w_i0 w_0j); weights
  // below `threshold` are treated as zero. Reuses storage: no allocation once grown.
  void build(const SingleScanProblem& problem, double threshold = 0.0);
  // Computes the clusters of the last build() (union-find over targets and measurements).
  void find_clusters();
  // Groups the edges of the last build() by measurement (targets stay in increasing order).
  void index_columns();

  int targets() const { return targets_; }
  int measurements() const { return measurements_; }
  int edges() const { return static_cast<int>(edge_measurement_.size()); }

  // Edges of target i are [row_begin(i), row_begin(i+1)), ordered by measurement index.
  int row_begin(int i) const { return row_start_[i]; }
  int row_end(int i) const { return row_start_[i + 1]; }
  int edge_measurement(int e) const { return edge_measurement_[e]; }  // 0-based measurement
  double edge_weight(int e) const { return edge_weight_[e]; }
  const double* edge_weights() const { return edge_weight_.data(); }  // edge_weight(e) for every e
  int measurement_degree(int j) const { return measurement_degree_[j]; }

  // Edges of measurement j (after index_columns()): column_edge(k) for k in
  // [column_begin(j), column_end(j)), in increasing target order.
  int column_begin(int j) const { return column_start_[j]; }
  int column_end(int j) const { return column_start_[j + 1]; }
  int column_edge(int k) const { return column_edge_[k]; }

  // Clusters (after find_clusters()): connected components over targets and measurements. Targets of cluster c are
  // cluster_targets()[cluster_start(c) .. cluster_start(c+1)), in increasing index order.
  // Each target is in exactly one cluster (an isolated target forms its own).
  int clusters() const { return static_cast<int>(cluster_start_.size()) - 1; }
  int cluster_start(int c) const { return cluster_start_[c]; }
  const std::vector<int>& cluster_targets() const { return cluster_targets_; }
  // The measurements of cluster c (after find_clusters()), in increasing order, into `out`; and
  // for each, local[j] = its index in `out` (local has m entries, −1 for other measurements on
  // entry and again after release_cluster_measurements(out, local)).
  void cluster_measurements(int c, std::vector<int>& out, std::vector<int>& local) const;
  static void release_cluster_measurements(const std::vector<int>& out, std::vector<int>& local);

 private:
  int find_root(int node);
  int targets_ = 0;
  int measurements_ = 0;
  std::vector<int> row_start_;
  std::vector<int> edge_measurement_;
  std::vector<double> edge_weight_;
  std::vector<int> measurement_degree_;
  std::vector<int> column_start_;
  std::vector<int> column_edge_;
  std::vector<int> parent_;  // union-find over targets (0..n-1) and measurements (n..n+m-1)
  std::vector<int> cluster_of_root_;
  std::vector<int> next_slot_;
  std::vector<int> cluster_start_;
  std::vector<int> cluster_targets_;
};

// The normaliser Z = 1 + Σ_e weight[e] of a row written by write_normalized_row, as two factors
// that stay finite where Z overflows: Z = largest · total.
struct RowNormalizer {
  double largest = 1.0;  // max(1, largest kept weight)
  double total = 1.0;    // 1/largest + Σ_e weight[e]/largest
};

// Writes target i's marginal row from unnormalised association weights (missed detection = 1,
// gated pair e = weight[e], indexed by the graph's edges): p(a_i = 0) = 1/Z, p(a_i = j) =
// weight[e]/Z — eq (12) for a target alone in its cluster, and the last step of the methods
// that reduce each target to such weights (BAA, LMIPDA). Weights below `floor` are left out (their
// entries untouched). Computed on the weights scaled by 1/max(1, largest), so no finite weight
// overflows the sum. `row` has m+1 entries and is already zero for ungated pairs.
RowNormalizer write_normalized_row(const AssociationGraph& graph, int i, const double* weight, double* row,
                                   double floor = 0.0);

// Whether some event gives every target that must be detected (problem.must_detect) its own
// gated measurement: a matching that covers them in the graph of the last build() (augmenting
// paths, Kuhn's algorithm; it allocates, and is called only for problems that have such
// targets). False: no event has positive weight, the problem is infeasible.
bool must_detect_feasible(const AssociationGraph& graph, const SingleScanProblem& problem);

}  // namespace dabench
