#include "algorithms/exact_enumeration.hpp"

#include <algorithm>

#include "harness/registry.hpp"

namespace dabench {

std::string ExactOptions::validate() const {
  if (!(threshold >= 0.0)) return "threshold must be >= 0";
  if (max_events < 1) return "max_events must be >= 1";
  return {};
}

// Depth-first enumeration over the cluster's targets in order_; `weight` is the product of the
// scaled weights chosen so far. At a leaf, the event's weight is added to the partition
// function and to the accumulator entry of every target's choice.
void ExactEnumeration::descend(int depth, double weight) {
  if (depth == static_cast<int>(order_.size())) {
    ++events_;
    partition_ += weight;
    for (int d = 0; d < depth; ++d) accumulator_[accumulator_row_[d] + choice_[d] + 1] += weight;
    return;
  }
  if (events_ > options_.max_events) return;
  const int target = order_[depth];
  const double scale = row_scale_[target];
  choice_[depth] = -1;
  descend(depth + 1, weight * scale);  // missed detection: ψ_i(0) = 1, scaled
  const int begin = graph_.row_begin(target);
  for (int e = begin; e < graph_.row_end(target); ++e) {
    const int j = graph_.edge_measurement(e);
    if (used_[j]) continue;
    used_[j] = 1;
    choice_[depth] = e - begin;
    descend(depth + 1, weight * graph_.edge_weight(e) * scale);
    used_[j] = 0;
  }
}

bool ExactEnumeration::enumerate_cluster(int first, int last, MarginalTable& marginals) {
  order_.assign(graph_.cluster_targets().begin() + first, graph_.cluster_targets().begin() + last);
  // Most constrained targets first keeps the search tree narrow near the root.
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
    return graph_.row_end(a) - graph_.row_begin(a) > graph_.row_end(b) - graph_.row_begin(b);
  });
  const int depth = static_cast<int>(order_.size());
  choice_.resize(depth);
  accumulator_row_.resize(depth);
  int size = 0;
  for (int d = 0; d < depth; ++d) {
    accumulator_row_[d] = size;
    size += graph_.row_end(order_[d]) - graph_.row_begin(order_[d]) + 1;
  }
  accumulator_.assign(size, 0.0);
  partition_ = 0.0;
  descend(0, 1.0);
  if (events_ > options_.max_events) return false;

  const double inverse = 1.0 / partition_;
  for (int d = 0; d < depth; ++d) {
    const int target = order_[d];
    const double* sums = accumulator_.data() + accumulator_row_[d];
    double* row = marginals.row(target);
    row[0] = sums[0] * inverse;
    for (int e = graph_.row_begin(target); e < graph_.row_end(target); ++e) {
      row[graph_.edge_measurement(e) + 1] = sums[e - graph_.row_begin(target) + 1] * inverse;
    }
  }
  return true;
}

void ExactEnumeration::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem, options_.threshold);
  graph_.find_clusters();
  const int n = graph_.targets();
  row_scale_.resize(n);
  for (int i = 0; i < n; ++i) {
    double largest = 1.0;
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) largest = std::max(largest, graph_.edge_weight(e));
    row_scale_[i] = 1.0 / largest;
  }
  used_.assign(graph_.measurements(), 0);
  marginals.reshape_zero(n, graph_.measurements());
  events_ = 0;
  for (int c = 0; c < graph_.clusters(); ++c) {
    if (!enumerate_cluster(graph_.cluster_start(c), graph_.cluster_start(c + 1), marginals)) {
      report.skipped = "work_limit";
      return;
    }
  }
}

DABENCH_REGISTER_SINGLE_SCAN(ExactEnumeration);

}  // namespace dabench
