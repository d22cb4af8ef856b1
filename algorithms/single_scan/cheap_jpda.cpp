#include "algorithms/single_scan/cheap_jpda.hpp"

#include <algorithm>
#include <cmath>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string CheapJpdaOptions::validate() const {
  if (!(bias >= 0.0 && std::isfinite(bias))) return "bias must be finite and >= 0";
  return {};
}

void CheapJpdaSolver::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  if (!(problem.largest_weight_sum() < SingleScanProblem::kOutOfRangeSum)) {
    report.skipped = "numerical";
    return;
  }
  graph_.build(problem);
  graph_.index_columns();
  const int n = graph_.targets();
  const int m = graph_.measurements();
  const int edges = graph_.edges();
  marginals.reshape_zero(n, m);

  row_sum_.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) row_sum_[i] += graph_.edge_weight(e);
  }
  term_.resize(edges);
  for (int i = 0; i < n; ++i) {
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
      const double w = graph_.edge_weight(e);
      term_[e] = variant_ == CheapJpdaVariant::fitzgerald ? w : w * (w / row_sum_[i]);
    }
  }
  // Leave-one-out sums of the terms over each measurement's gated targets: prefix, then suffix.
  others_.assign(edges, 0.0);
  for (int j = 0; j < m; ++j) {
    double run = 0.0;
    for (int k = graph_.column_begin(j); k < graph_.column_end(j); ++k) {
      const int e = graph_.column_edge(k);
      others_[e] = run;
      run += term_[e];
    }
    run = 0.0;
    for (int k = graph_.column_end(j); k-- > graph_.column_begin(j);) {
      const int e = graph_.column_edge(k);
      others_[e] += run;
      run += term_[e];
    }
  }
  for (int i = 0; i < n; ++i) {
    double* row = marginals.row(i);
    double assigned = 0.0;
    for (int e = graph_.row_begin(i); e < graph_.row_end(i); ++e) {
      const double beta = graph_.edge_weight(e) / (row_sum_[i] + others_[e] + options_.bias);
      row[graph_.edge_measurement(e) + 1] = beta;
      assigned += beta;
    }
    row[0] = std::max(0.0, 1.0 - assigned);  // 1 for a target with no gated measurement; B = 0 may round below 0
  }
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(CheapJpda);
DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(ModifiedCheapJpda);

}  // namespace dabench
