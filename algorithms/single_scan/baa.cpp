#include "algorithms/single_scan/baa.hpp"

#include <algorithm>

#include "harness/single_scan/registry.hpp"

namespace dabench {


void BakhtiarAlaviAmoozegar::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  const int n = graph_.targets();
  const int m = graph_.measurements();
  const int edges = graph_.edges();
  marginals.reshape_zero(n, m);

  bool shared = false;
  for (int j = 0; j < m && !shared; ++j) shared = graph_.measurement_degree(j) >= 2;
  product_.assign(edges, 1.0);
  if (shared) {
    // f_ij = (1 + Σ_{k≠j} ψ_ik) / (1 + Σ_k ψ_ik), on weights scaled by 1/max(1, max_k ψ_ik):
    // prefix sums forwards (stored in factor_), suffix sums backwards.
    factor_.resize(edges);
    for (int i = 0; i < n; ++i) {
      const int begin = graph_.row_begin(i);
      const int end = graph_.row_end(i);
      double largest = 1.0;
      for (int e = begin; e < end; ++e) largest = std::max(largest, graph_.edge_weight(e));
      const double scale = 1.0 / largest;
      double run = 0.0;
      for (int e = begin; e < end; ++e) {
        factor_[e] = run;
        run += graph_.edge_weight(e) * scale;
      }
      const double inverse_total = 1.0 / (scale + run);  // 1 / (scaled S_i)
      run = 0.0;
      for (int e = end; e-- > begin;) {
        factor_[e] = (scale + factor_[e] + run) * inverse_total;
        run += graph_.edge_weight(e) * scale;
      }
    }
    // Π_{i≠t} f_ij per edge (t, j): leave-one-out products over the targets gated to j.
    graph_.index_columns();
    for (int j = 0; j < m; ++j) {
      const int begin = graph_.column_begin(j);
      const int end = graph_.column_end(j);
      if (end - begin < 2) continue;
      double run = 1.0;
      for (int k = begin; k < end; ++k) {
        const int e = graph_.column_edge(k);
        product_[e] = run;
        run *= factor_[e];
      }
      run = 1.0;
      for (int k = end; k-- > begin;) {
        const int e = graph_.column_edge(k);
        product_[e] *= run;
        run *= factor_[e];
      }
    }
  }

  // β_tj / β_t0 = ψ_tj · Π_{i≠t} f_ij; rows normalised on weights scaled by 1/max(1, largest).
  for (int t = 0; t < n; ++t) {
    const int begin = graph_.row_begin(t);
    const int end = graph_.row_end(t);
    for (int e = begin; e < end; ++e) product_[e] *= graph_.edge_weight(e);
    write_normalized_row(graph_, t, product_.data(), marginals.row(t));
  }
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(BakhtiarAlaviAmoozegar);

}  // namespace dabench
