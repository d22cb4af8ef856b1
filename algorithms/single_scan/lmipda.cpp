#include "algorithms/single_scan/lmipda.hpp"

#include <algorithm>

#include "harness/single_scan/registry.hpp"

namespace dabench {

std::string LmipdaOptions::validate() const {
  if (!std::isnan(pd) && !(pd > 0.0 && pd < 1.0)) return "pd must be in (0, 1) (or left unset)";
  if (!(pg > 0.0 && pg <= 1.0)) return "pg must be in (0, 1]";
  return {};
}


void Lmipda::solve(const SingleScanProblem& problem, MarginalTable& marginals, SolveReport& report) {
  report.reset();
  graph_.build(problem);
  const int n = graph_.targets();
  const int m = graph_.measurements();
  const int edges = graph_.edges();

  bool shared = false;
  for (int j = 0; j < m && !shared; ++j) shared = graph_.measurement_degree(j) >= 2;
  const double pd = std::isnan(options_.pd) ? problem.context.pd : options_.pd;
  const bool pd_known = pd > 0.0 && pd < 1.0;  // false for NaN
  const double pg = options_.pg;
  if ((shared || (pg < 1.0 && edges > 0)) && !pd_known) {
    report.skipped = "needs_pd";
    return;
  }
  marginals.reshape_zero(n, m);

  // β_τi/β_τ0 = ψ_τi · gain / (1 + spread · Σ_{η≠τ} clutter_share_ηi).
  const double gain = pg < 1.0 ? (1.0 - pd) / (1.0 - pd * pg) : 1.0;
  others_.assign(edges, 0.0);
  if (shared) {
    const double pdpg = pd * pg;
    const double spread = (1.0 - pd) / pdpg;
    // P^η_i = Pd·Pg·ψ_ηi / Σ_j ψ_ηj (row sums on scaled weights), and the share of measurement i
    // that track η contributes to every other track's modulated clutter density (over ρ_i).
    clutter_share_.resize(edges);
    for (int i = 0; i < n; ++i) {
      const int begin = graph_.row_begin(i);
      const int end = graph_.row_end(i);
      double largest = 1.0;
      for (int e = begin; e < end; ++e) largest = std::max(largest, graph_.edge_weight(e));
      const double scale = 1.0 / largest;
      double total = 0.0;
      for (int e = begin; e < end; ++e) total += graph_.edge_weight(e) * scale;
      for (int e = begin; e < end; ++e) {
        const double psi = graph_.edge_weight(e);
        const double prior = pdpg * (psi * scale / total);  // P^η_i ≤ Pd·Pg < 1
        clutter_share_[e] = spread * psi * (prior / (1.0 - prior));
      }
    }
    // Leave-one-out sums per measurement: prefix sums forwards, then suffix sums backwards.
    graph_.index_columns();
    for (int j = 0; j < m; ++j) {
      const int begin = graph_.column_begin(j);
      const int end = graph_.column_end(j);
      if (end - begin < 2) continue;
      double run = 0.0;
      for (int k = begin; k < end; ++k) {
        const int e = graph_.column_edge(k);
        others_[e] = run;
        run += clutter_share_[e];
      }
      run = 0.0;
      for (int k = end; k-- > begin;) {
        const int e = graph_.column_edge(k);
        others_[e] += run;
        run += clutter_share_[e];
      }
    }
  }

  // PDA per track with the modulated clutter density; rows normalised on weights scaled by
  // 1/max(1, largest weight) so that no finite ψ overflows the sum.
  for (int i = 0; i < n; ++i) {
    const int begin = graph_.row_begin(i);
    const int end = graph_.row_end(i);
    for (int e = begin; e < end; ++e) {
      others_[e] = gain * graph_.edge_weight(e) / (1.0 + others_[e]);  // now the association weight
    }
    write_normalized_row(graph_, i, others_.data(), marginals.row(i));
  }
}

DABENCH_REGISTER_SINGLE_SCAN_ALGORITHM(Lmipda);

}  // namespace dabench
