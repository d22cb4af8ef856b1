#include "algorithms/single_scan/exact_enumeration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string ExactOptions::validate() const {
  if (!(threshold >= 0.0)) return "threshold must be >= 0";
  if (max_events < 1) return "max_events must be >= 1";
  return {};
}

// Depth-first enumeration over the cluster's targets in order_; `prefix` is the product of the
// scaled weights chosen above. Returns the summed weight of every completion below this node,
// so each choice's share of the partition function, prefix · w · (completions below), is added
// once per search-tree node instead of once per event and target.
double ExactEnumeration::descend(int depth, double prefix) {
  if (depth == static_cast<int>(order_.size())) {
    ++events_;
    return 1.0;
  }
  if (events_ > options_.max_events) return 0.0;  // abandoned: the caller reports skipped
  const int target = order_[depth];
  const double scale = row_scale_[target];
  double* sums = accumulator_.data() + accumulator_row_[depth];
  double total = 0.0;
  if (!must_detect_[target]) {
    const double below = descend(depth + 1, prefix * scale);  // missed detection: ψ_i(0) = 1, scaled
    sums[0] += prefix * scale * below;
    total = scale * below;
  }
  const int begin = graph_.row_begin(target);
  for (int e = begin; e < graph_.row_end(target); ++e) {
    const int j = graph_.edge_measurement(e);
    if (used_[j]) continue;
    used_[j] = 1;
    const double w = graph_.edge_weight(e) * scale;
    const double below = descend(depth + 1, prefix * w);
    used_[j] = 0;
    sums[e - begin + 1] += prefix * w * below;
    total += w * below;
  }
  return total;
}

std::string_view ExactEnumeration::enumerate_cluster(int first, int last, MarginalTable& marginals) {
  order_.assign(graph_.cluster_targets().begin() + first, graph_.cluster_targets().begin() + last);
  // Most constrained targets first keeps the search tree narrow near the root.
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
    return graph_.row_end(a) - graph_.row_begin(a) > graph_.row_end(b) - graph_.row_begin(b);
  });
  const int depth = static_cast<int>(order_.size());
  accumulator_row_.resize(depth);
  int size = 0;
  for (int d = 0; d < depth; ++d) {
    accumulator_row_[d] = size;
    size += graph_.row_end(order_[d]) - graph_.row_begin(order_[d]) + 1;
  }
  accumulator_.assign(size, 0.0);
  const double partition = descend(0, 1.0);
  if (events_ > options_.max_events) return "work_limit";
  // Scaled weights are ≤ 1, so a product that underflows loses less than the smallest subnormal,
  // and a completion count (≤ the events) is the most such a loss is later multiplied by: the
  // mass lost is below 4 · events² · depth · 2^−1074. Where that is not 1e−12 of the partition
  // function (weights whose products leave double's range, e.g. one ψ = 1e30 gated by 12
  // targets), the marginals are not computed from it.
  const double events = static_cast<double>(events_);
  const double lost = 4.0 * events * events * depth * std::numeric_limits<double>::denorm_min();
  if (!(partition > 1e12 * lost) || !std::isfinite(partition)) return "numerical";

  const double inverse = 1.0 / partition;
  for (int d = 0; d < depth; ++d) {
    const int target = order_[d];
    const double* sums = accumulator_.data() + accumulator_row_[d];
    double* row = marginals.row(target);
    row[0] = sums[0] * inverse;
    for (int e = graph_.row_begin(target); e < graph_.row_end(target); ++e) {
      row[graph_.edge_measurement(e) + 1] = sums[e - graph_.row_begin(target) + 1] * inverse;
    }
  }
  return {};
}

void ExactEnumeration::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem, options_.threshold);
  if (problem.has_must_detect_targets() && !must_detect_feasible(graph_, problem)) {
    report.skipped = "infeasible";
    return;
  }
  graph_.find_clusters();
  const int n = graph_.targets();
  row_scale_.resize(n);
  must_detect_.resize(n);
  for (int i = 0; i < n; ++i) {
    must_detect_[i] = problem.must_detect(i);
    double largest = 1.0;
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) largest = std::max(largest, graph_.edge_weight(e));
    row_scale_[i] = 1.0 / largest;
  }
  used_.assign(graph_.measurements(), 0);
  marginals.reshape_zero(n, graph_.measurements());
  events_ = 0;
  for (int c = 0; c < graph_.clusters(); ++c) {
    if (const std::string_view refused = enumerate_cluster(graph_.cluster_start(c), graph_.cluster_start(c + 1), marginals);
        !refused.empty()) {
      report.skipped = refused;
      return;
    }
  }
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(ExactEnumeration);

}  // namespace dabench
