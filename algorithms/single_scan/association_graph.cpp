#include "algorithms/single_scan/association_graph.hpp"

#include <algorithm>

namespace dabench {

int AssociationGraph::find_root(int node) {
  while (parent_[node] != node) {
    parent_[node] = parent_[parent_[node]];  // path halving
    node = parent_[node];
  }
  return node;
}

void AssociationGraph::build(const SingleScanProblem& problem, double threshold) {
  targets_ = problem.targets();
  measurements_ = problem.measurements();
  row_start_.assign(targets_ + 1, 0);
  edge_measurement_.clear();
  edge_weight_.clear();
  measurement_degree_.assign(measurements_, 0);

  const bool unit = problem.has_unit_side_weights();
  for (int i = 0; i < targets_; ++i) {
    for (int j = 0; j < measurements_; ++j) {
      const double w = unit ? problem.psi(i, j) : problem.normalized_weight(i, j);
      if (w <= 0.0 || w < threshold) continue;
      edge_measurement_.push_back(j);
      edge_weight_.push_back(w);
      ++measurement_degree_[j];
    }
    row_start_[i + 1] = static_cast<int>(edge_measurement_.size());
  }
}

void AssociationGraph::index_columns() {
  column_start_.assign(measurements_ + 1, 0);
  for (int j = 0; j < measurements_; ++j) column_start_[j + 1] = column_start_[j] + measurement_degree_[j];
  next_slot_.assign(column_start_.begin(), column_start_.end() - 1);
  column_edge_.resize(edge_measurement_.size());
  for (int e = 0; e < edges(); ++e) column_edge_[next_slot_[edge_measurement_[e]]++] = e;
}

void AssociationGraph::find_clusters() {
  parent_.resize(targets_ + measurements_);
  for (int v = 0; v < targets_ + measurements_; ++v) parent_[v] = v;
  for (int i = 0; i < targets_; ++i) {
    for (int e = row_start_[i]; e < row_start_[i + 1]; ++e) {
      const int a = find_root(i);
      const int b = find_root(targets_ + edge_measurement_[e]);
      if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }
  }

  // Number clusters by their smallest target, then list targets cluster by cluster.
  cluster_of_root_.assign(targets_ + measurements_, -1);
  int count = 0;
  for (int i = 0; i < targets_; ++i) {
    const int root = find_root(i);
    if (cluster_of_root_[root] < 0) cluster_of_root_[root] = count++;
  }
  cluster_start_.assign(count + 1, 0);
  for (int i = 0; i < targets_; ++i) ++cluster_start_[cluster_of_root_[find_root(i)] + 1];
  for (int c = 0; c < count; ++c) cluster_start_[c + 1] += cluster_start_[c];
  cluster_targets_.resize(targets_);
  next_slot_.assign(cluster_start_.begin(), cluster_start_.end() - 1);
  for (int i = 0; i < targets_; ++i) cluster_targets_[next_slot_[cluster_of_root_[find_root(i)]]++] = i;
}

void AssociationGraph::cluster_measurements(int c, std::vector<int>& out, std::vector<int>& local) const {
  out.clear();
  for (int t = cluster_start_[c]; t < cluster_start_[c + 1]; ++t) {
    const int i = cluster_targets_[t];
    for (int e = row_start_[i]; e < row_start_[i + 1]; ++e) {
      const int j = edge_measurement_[e];
      if (local[j] < 0) {
        local[j] = 0;
        out.push_back(j);
      }
    }
  }
  std::sort(out.begin(), out.end());
  for (std::size_t k = 0; k < out.size(); ++k) local[out[k]] = static_cast<int>(k);
}

void AssociationGraph::release_cluster_measurements(const std::vector<int>& out, std::vector<int>& local) {
  for (const int j : out) local[j] = -1;
}

RowNormalizer write_normalized_row(const AssociationGraph& graph, int i, const double* weight, double* row,
                                   double floor) {
  const int begin = graph.row_begin(i);
  const int end = graph.row_end(i);
  RowNormalizer z;
  for (int e = begin; e < end; ++e) {
    if (!(weight[e] < floor)) z.largest = std::max(z.largest, weight[e]);
  }
  const double scale = 1.0 / z.largest;
  z.total = scale;
  for (int e = begin; e < end; ++e) {
    if (!(weight[e] < floor)) z.total += weight[e] * scale;
  }
  const double inverse = 1.0 / z.total;
  row[0] = scale * inverse;
  for (int e = begin; e < end; ++e) {
    if (!(weight[e] < floor)) row[graph.edge_measurement(e) + 1] = weight[e] * scale * inverse;
  }
  return z;
}

bool must_detect_feasible(const AssociationGraph& graph, const SingleScanProblem& problem) {
  std::vector<int> owner(static_cast<std::size_t>(graph.measurements()), -1);  // the target holding j
  std::vector<int> visited(static_cast<std::size_t>(graph.measurements()), -1);  // stamp: the search
  // Finds a measurement for target i, moving earlier holders along an augmenting path.
  const auto augment = [&](int i, int stamp, const auto& self) -> bool {
    for (int e = graph.row_begin(i); e < graph.row_end(i); ++e) {
      const int j = graph.edge_measurement(e);
      if (visited[static_cast<std::size_t>(j)] == stamp) continue;
      visited[static_cast<std::size_t>(j)] = stamp;
      const int holder = owner[static_cast<std::size_t>(j)];
      if (holder < 0 || self(holder, stamp, self)) {
        owner[static_cast<std::size_t>(j)] = i;
        return true;
      }
    }
    return false;
  };
  for (int i = 0; i < graph.targets(); ++i) {
    if (problem.must_detect(i) && !augment(i, i, augment)) return false;
  }
  return true;
}

}  // namespace dabench
