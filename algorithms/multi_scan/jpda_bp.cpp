#include "algorithms/multi_scan/jpda_bp.hpp"

#include "harness/multi_scan/registry.hpp"

namespace dabench {

std::string JpdaBpOptions::validate() const {
  if (!(delta > 0.0)) return "delta must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  return {};
}

JpdaBp::JpdaBp(const Options& options)
    : options_(options), bp_(BpOptions{.delta = options.delta, .max_iterations = options.max_iterations}) {}

void JpdaBp::solve(const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) {
  report.reset();
  const int n = problem.tracks();
  beliefs.track.resize(n);
  for (int i = 0; i < n; ++i) beliefs.track[i] = problem.prior[i] / problem.prior[i].sum();
  beliefs.association.resize(problem.scan_count());
  SolveReport scan_report;
  for (int t = 0; t < problem.scan_count(); ++t) {
    const ScanFactors& scan = problem.scans[t];
    const int m = scan.measurements;
    // 1. w^{i,j} = Σ_p q^i(p) ψ^i_t(p, j).
    weights_.resize(n, m + 1);
    for (int i = 0; i < n; ++i) weights_.row(i) = beliefs.track[i].transpose() * scan.factor[i];
    // 2. Single-scan BP on ψ_i(j) = w^{i,j} / w^{i,0}.
    scan_problem_.psi.resize(n, m);
    for (int i = 0; i < n; ++i) {
      if (!(weights_(i, 0) > 0.0)) {
        report.skipped = "zero_miss_weight";
        return;
      }
      for (int j = 1; j <= m; ++j) scan_problem_.psi(i, j - 1) = weights_(i, j) / weights_(i, 0);
    }
    MarginalTable& marginals = beliefs.association[t];
    bp_.solve(scan_problem_, marginals, scan_report);
    if (!scan_report.skipped.empty()) {
      report.skipped = scan_report.skipped;
      return;
    }
    report.iterations += scan_report.iterations;
    report.converged = report.converged && scan_report.converged;
    // 3. q^i(p) ∝ q^i(p) Σ_j P(a_i = j) ψ^i_t(p, j) / w^{i,j}.
    for (int i = 0; i < n; ++i) {
      Vector& q = beliefs.track[i];
      const RowMatrix& factor = scan.factor[i];
      for (Eigen::Index p = 0; p < q.size(); ++p) {
        double likelihood = 0.0;
        for (int j = 0; j <= m; ++j) {
          if (weights_(i, j) > 0.0) likelihood += marginals(i, j) * factor(p, j) / weights_(i, j);
        }
        q[p] *= likelihood;
      }
      q /= q.sum();
    }
  }
}

DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(JpdaBp);

}  // namespace dabench
