#include "algorithms/single_scan/kbest_jpda.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string KBestJpdaOptions::validate() const {
  if (k < 1) return "k must be >= 1";
  if (mass_memory_mb < 0) return "mass_memory_mb must be >= 0";
  return {};
}

void KBestJpda::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  graph_.find_clusters();
  const int n = graph_.targets(), m = graph_.measurements();
  marginals.reshape_zero(n, m);
  local_measurement_.assign(static_cast<std::size_t>(m), -1);
  const std::vector<int>& members = graph_.cluster_targets();
  constexpr double kForbidden = std::numeric_limits<double>::infinity();
  long long events = 0;
  bool complete = true;
  // The permanent's sums overflow where ψ's row or column sums do: no mass then.
  double log_captured = options_.mass_memory_mb > 0 && problem.largest_weight_sum() < SingleScanProblem::kOutOfRangeSum
                            ? 0.0
                            : std::numeric_limits<double>::quiet_NaN();
  for (int c = 0; c < graph_.clusters(); ++c) {
    graph_.cluster_measurements(c, cluster_measurements_, local_measurement_);
    const int rows = graph_.cluster_start(c + 1) - graph_.cluster_start(c);
    const int cols = static_cast<int>(cluster_measurements_.size());
    const std::size_t cells = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
    cost_.assign(cells, kForbidden);
    dense_.assign(cells, 0.0);
    miss_cost_.assign(static_cast<std::size_t>(rows), 0.0);  // −log ψ_i(0) = −log 1
    for (int r = 0; r < rows; ++r) {
      const int i = members[graph_.cluster_start(c) + r];
      for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
        const std::size_t cell = static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) +
                                 static_cast<std::size_t>(local_measurement_[graph_.edge_measurement(e)]);
        dense_[cell] = graph_.edge_weight(e);
        cost_[cell] = -std::log(graph_.edge_weight(e));
      }
    }
    murty_.solve(cost_.data(), miss_cost_.data(), rows, cols, options_.k, ranked_);
    events += ranked_.size();
    if (ranked_.size() >= options_.k) complete = false;
    // Kept events' weights relative to the best: exp(−(cost − best)) ≤ 1.
    const double best = ranked_.cost(0);
    double kept = 0.0;
    for (int event = 0; event < ranked_.size(); ++event) {
      const double w = std::exp(best - ranked_.cost(event));
      kept += w;
      const auto columns = ranked_.columns(event);
      for (int r = 0; r < rows; ++r) {
        const int i = members[graph_.cluster_start(c) + r];
        const int column = columns[static_cast<std::size_t>(r)];
        marginals(i, column < 0 ? 0 : cluster_measurements_[static_cast<std::size_t>(column)] + 1) += w;
      }
    }
    for (int r = 0; r < rows; ++r) {
      double* row = marginals.row(members[graph_.cluster_start(c) + r]);
      for (int j = 0; j <= m; ++j) row[j] /= kept;
    }
    if (!std::isnan(log_captured) && SubsetPermanent::fits(rows, cols, options_.mass_memory_mb)) {
      log_captured += (std::log(kept) - best) - permanent_.log_partition(dense_.data(), rows, cols);
    } else {
      log_captured = std::numeric_limits<double>::quiet_NaN();
    }
    AssociationGraph::release_cluster_measurements(cluster_measurements_, local_measurement_);
  }
  report.iterations = static_cast<int>(std::min<long long>(events, std::numeric_limits<int>::max()));
  report.converged = complete;
  report.captured_mass = std::isnan(log_captured) ? log_captured : std::min(1.0, std::exp(log_captured));
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(KBestJpda);

}  // namespace dabench
